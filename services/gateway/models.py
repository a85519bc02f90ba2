"""Response models of the gateway's HTTP API.

Bus messages are not redefined here: they are served as the proto3 JSON mapping of their
coopdrive.v1 message (field names as in the .proto), so the proto stays their one definition.
"""

from __future__ import annotations

from enum import Enum
from typing import Any

from pydantic import BaseModel, Field


class HealthStatus(str, Enum):
    OK = "ok"  # every required service alive and publishing
    DEGRADED = "degraded"  # some required service down or silent
    DOWN = "down"  # no required service alive


class ServiceStatus(str, Enum):
    RUNNING = "running"  # alive and publishing
    SILENT = "silent"  # alive, but nothing recent on its topics
    DOWN = "down"  # no liveliness token


class ServiceHealth(BaseModel):
    service: str = Field(description="Service name, e.g. 'planner'.")
    participant: str = Field(description="'<vehicle>/<service>' as in the liveliness tokens ('world/sim').")
    required: bool = Field(description="Whether its absence degrades the overall status.")
    alive: bool = Field(description="Its liveliness token is present on the bus.")
    status: ServiceStatus
    last_message_age_s: float | None = Field(
        description="Vehicle clock now minus the send time of its newest message; null if none seen.")
    message_rate_hz: float = Field(description="Messages per wall-clock second over the rate window, all topics.")
    topics: list[str] = Field(description="The topics this service publishes (topic registry).")


class StationReception(BaseModel):
    """A remote ITS station's link as /health summarises it (the full row is in /v2x/stations)."""
    station_id: int
    active: bool = Field(description="Heard within the v2x service's link timeout.")
    reception_ratio: float = Field(description="Received over expected messages, [0, 1].")
    expected_cam_rate_hz: float = Field(description="The rate its CAMs are judged at: the profile's (GCDC: 25 Hz) or "
                                        "the station's own median rate (EN 302 637-2 stations: 1-10 Hz).")


class HealthResponse(BaseModel):
    status: HealthStatus
    vehicle_id: str
    clock_s: float | None = Field(description="The vehicle clock the ages are measured against (sim time in a run).")
    services: dict[str, ServiceHealth]
    v2x_stations: list[StationReception] = Field(
        default_factory=list, description="Each remote station's reception, from the latest v2x/status.")
    bus_mode: str = Field(default="", description="How the gateway's bus session reaches the others: 'mtls' "
                          "(authenticated by its certificate), 'plain-loopback' (this computer only) or 'plain'.")


class MessageEntry(BaseModel):
    type_name: str = Field(description="Full protobuf type name, e.g. 'coopdrive.v1.EgoState'.")
    age_s: float | None = Field(description="Vehicle clock now minus header.sent_time_s.")
    message: dict[str, Any] = Field(description="The message in the proto3 JSON mapping, proto field names.")


class StateResponse(BaseModel):
    vehicle_id: str
    clock_s: float | None
    ego_state: MessageEntry | None = Field(description="Latest coopdrive.v1.EgoState (topic ego/state).")
    scene: MessageEntry | None = Field(description="Latest coopdrive.v1.Scene (topic scene).")
    planner_state: MessageEntry | None = Field(description="Latest coopdrive.v1.PlannerState (topic planner/state).")
    control_command: MessageEntry | None = Field(
        description="Latest coopdrive.v1.ControlCommand (topic control/command).")
    actuation_status: MessageEntry | None = Field(
        description="Latest coopdrive.v1.ActuationStatus (topic actuation/status).")
