"""Turns a StateStore snapshot into the /health and /state responses (no network, no clock)."""

from __future__ import annotations

from google.protobuf.json_format import MessageToDict

from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.pipeline import participant_name
from coopdrive.services.gateway.models import (
    HealthResponse,
    HealthStatus,
    MessageEntry,
    ServiceHealth,
    ServiceStatus,
    StateResponse,
    StationReception,
)
from coopdrive.services.gateway.state_store import LatestMessage, StoreSnapshot

# /state field -> the topic whose latest message it carries.
STATE_TOPICS = {
    "ego_state": "ego/state",
    "scene": "scene",
    "planner_state": "planner/state",
    "control_command": "control/command",
    "actuation_status": "actuation/status",
}
# Microseconds: enough for any step, without float noise like 0.019999999999999574.
AGE_DECIMALS = 6
# The simulator is one for the whole world, not per vehicle.
WORLD_SERVICES = ("sim",)


def service_participant(vehicle_id: str, service: str) -> str:
    return participant_name(WORLD_ID if service in WORLD_SERVICES else vehicle_id, service)


def message_age_s(clock_s: float | None, sent_time_s: float | None) -> float | None:
    if clock_s is None or sent_time_s is None:
        return None
    # The gateway hears the clock after the publishers do, so it may trail them by a step.
    return round(max(0.0, clock_s - sent_time_s), AGE_DECIMALS)


def health_report(snapshot: StoreSnapshot, vehicle_id: str, topics_by_service: dict[str, list[str]],
                  required: list[str], silent_after_s: float,
                  v2x_stations: list[StationReception] | None = None, bus_mode: str = "") -> HealthResponse:
    services: dict[str, ServiceHealth] = {}
    for service, activity in snapshot.services.items():
        age_s = message_age_s(snapshot.clock_s, activity.last_sent_time_s)
        if not activity.alive:
            status = ServiceStatus.DOWN
        elif activity.message_rate_hz <= 0 or age_s is None or age_s > silent_after_s:
            status = ServiceStatus.SILENT
        else:
            status = ServiceStatus.RUNNING
        services[service] = ServiceHealth(
            service=service, participant=service_participant(vehicle_id, service), required=service in required,
            alive=activity.alive, status=status, last_message_age_s=age_s,
            message_rate_hz=round(activity.message_rate_hz, 3), topics=topics_by_service.get(service, []))
    needed = [services[name] for name in required if name in services]
    if needed and all(s.status is ServiceStatus.RUNNING for s in needed):
        overall = HealthStatus.OK
    elif any(s.alive for s in needed):
        overall = HealthStatus.DEGRADED
    else:
        overall = HealthStatus.DOWN
    return HealthResponse(status=overall, vehicle_id=vehicle_id, clock_s=snapshot.clock_s, services=services,
                          v2x_stations=v2x_stations or [], bus_mode=bus_mode)


def message_entry(latest: LatestMessage | None, clock_s: float | None) -> MessageEntry | None:
    if latest is None:
        return None
    body = MessageToDict(latest.message, preserving_proto_field_name=True, always_print_fields_with_no_presence=True)
    return MessageEntry(type_name=latest.message.DESCRIPTOR.full_name,
                        age_s=message_age_s(clock_s, latest.sent_time_s), message=body)


def state_report(snapshot: StoreSnapshot, vehicle_id: str) -> StateResponse:
    entries = {field: message_entry(snapshot.latest.get(topic), snapshot.clock_s)
               for field, topic in STATE_TOPICS.items()}
    return StateResponse(vehicle_id=vehicle_id, clock_s=snapshot.clock_s, **entries)
