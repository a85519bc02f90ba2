"""Builds the /v2x/stations, /scene, /planner views and the /ws live frames from a store snapshot.

No network and no clock: the caller passes the snapshot and the latest planner graph.
"""

from __future__ import annotations

import math

from coopdrive.services.gateway.models import StationReception
from coopdrive.services.gateway.reports import message_age_s
from coopdrive.services.gateway.state_store import StoreSnapshot
from coopdrive.services.gateway.view_models import (
    LinkStateName,
    LiveAvailability,
    LiveFrame,
    LiveObject,
    LiveStation,
    PlannerResponse,
    PositionView,
    PropertyView,
    SceneObjectView,
    SceneResponse,
    StationView,
    TransitionView,
    V2xStationsResponse,
)
from coopdrive.messages.unknowns import DEFAULT_LENGTH_M, DEFAULT_WIDTH_M, UNKNOWN_CONFIDENCE
from coopdrive.v1 import actuation_pb2, header_pb2, planner_pb2, scene_pb2, sensors_pb2, v2x_pb2

DEFAULT_LANE_WIDTH_M = 3.5
# Below this speed a time gap means nothing (standing still).
MIN_SPEED_FOR_TIME_GAP_MPS = 0.5
LINK_STATES = {v2x_pb2.LINK_STATE_ACTIVE: LinkStateName.ACTIVE, v2x_pb2.LINK_STATE_LOST: LinkStateName.LOST}


def enum_label(enum_type, value: int) -> str:
    """'OBJECT_CLASS_EMERGENCY_VEHICLE' -> 'emergency_vehicle': the proto name without its type prefix."""
    name = enum_type.Name(value) if value in enum_type.values() else f"UNKNOWN_{value}"
    prefix = "_".join(part.upper() for part in _split_camel(enum_type.DESCRIPTOR.name)) + "_"
    return name.removeprefix(prefix).lower()


def _split_camel(name: str) -> list[str]:
    parts, current = [], ""
    for char in name:
        if char.isupper() and current:
            parts.append(current)
            current = ""
        current += char
    return parts + [current]


def _sources(sources) -> list[str]:
    return [enum_label(header_pb2.SensorSource, s) for s in sources]


def _property(prop) -> PropertyView:
    known = prop.confidence != UNKNOWN_CONFIDENCE
    return PropertyView(value=float(prop.value) if known else None, confidence=prop.confidence if known else None,
                        sources=_sources(prop.sources))


def _latest(snapshot: StoreSnapshot, topic: str):
    latest = snapshot.latest.get(topic)
    return (latest.message, message_age_s(snapshot.clock_s, latest.sent_time_s)) if latest else (None, None)


def _station_link(station: v2x_pb2.StationLinkStats) -> LinkStateName:
    return LINK_STATES.get(station.state, LinkStateName.UNSPECIFIED)


def scene_trust(snapshot: StoreSnapshot) -> dict[int, float]:
    """The scene's trust in each V2V station it knows (the v2x service itself keeps none)."""
    scene, _ = _latest(snapshot, "scene")
    return {station.station_id: station.trust for station in scene.station_trust} if scene is not None else {}


def station_reception(status: v2x_pb2.V2xStatus) -> list[StationReception]:
    return [StationReception(station_id=s.station_id, active=s.state == v2x_pb2.LINK_STATE_ACTIVE,
                             reception_ratio=s.reception_ratio, expected_cam_rate_hz=s.expected_cam_rate_hz)
            for s in status.stations]


def v2x_reception(snapshot: StoreSnapshot) -> list[StationReception]:
    """/health's V2X part: each station's reception ratio at its expected rate."""
    status, _ = _latest(snapshot, "v2x/status")
    return station_reception(status) if status is not None else []


def v2x_view(snapshot: StoreSnapshot, vehicle_id: str) -> V2xStationsResponse:
    status, age_s = _latest(snapshot, "v2x/status")
    status = status or v2x_pb2.V2xStatus()
    trust = scene_trust(snapshot)
    stations = [StationView(
        station_id=s.station_id, state=_station_link(s), last_heard_s=s.last_heard_s,
        message_rate_hz=s.message_rate_hz, reception_ratio=s.reception_ratio,
        expected_cam_rate_hz=s.expected_cam_rate_hz, clock_offset_s=s.clock_offset_s,
        clock_diagnostic=s.clock_diagnostic, update_delay_p50_s=s.update_delay_p50_s, update_delay_p95_s=s.update_delay_p95_s,
        update_delay_max_s=s.update_delay_max_s, messages_received=s.messages_received,
        messages_rejected=s.messages_rejected, trust=trust.get(s.station_id, s.trust), signed=s.signed,
        verified=s.verified,
        trusted=s.trusted, messages_signed=s.messages_signed, messages_verified=s.messages_verified,
        messages_trusted=s.messages_trusted, messages_untrusted=s.messages_untrusted,
        signature_failures=s.signature_failures,
        messages_refused_by_security=s.messages_refused_by_security, last_security_reason=s.last_security_reason)
        for s in status.stations]
    return V2xStationsResponse(
        vehicle_id=vehicle_id, clock_s=snapshot.clock_s, age_s=age_s, stations=stations,
        active_count=sum(s.state is LinkStateName.ACTIVE for s in stations),
        lost_count=sum(s.state is LinkStateName.LOST for s in stations),
        packets_sent=status.packets_sent, packets_received=status.packets_received,
        rejected_by_reason=dict(status.rejected_by_reason))


def _object_view(obj: scene_pb2.SceneObject, scene: scene_pb2.Scene) -> SceneObjectView:
    p = obj.position
    known = p.confidence != UNKNOWN_CONFIDENCE
    return SceneObjectView(
        object_id=obj.object_id, object_class=enum_label(sensors_pb2.ObjectClass, obj.object_class),
        position=PositionView(x_m=p.x_m if known else None, y_m=p.y_m if known else None, std_m=p.std_m,
                              confidence=p.confidence if known else None, sources=_sources(p.sources)),
        speed_mps=_property(obj.speed_mps), accel_mps2=_property(obj.accel_mps2),
        heading_rad=_property(obj.heading_rad), length_m=_property(obj.length_m), width_m=_property(obj.width_m),
        lane_index=_property(obj.lane_index), station_id=_property(obj.station_id),
        longitudinal_gap_m=obj.longitudinal_gap_m, lateral_offset_m=obj.lateral_offset_m,
        relative_speed_mps=obj.relative_speed_mps, v2v_trust=obj.v2v_trust, ghost=obj.ghost,
        first_seen_s=obj.first_seen_s, is_mio=scene.has_mio and obj.object_id == scene.mio_id,
        is_forward_mio=scene.has_forward_mio and obj.object_id == scene.forward_mio_id)


def scene_view(snapshot: StoreSnapshot, vehicle_id: str) -> SceneResponse:
    scene, age_s = _latest(snapshot, "scene")
    if scene is None:
        return SceneResponse(vehicle_id=vehicle_id, clock_s=snapshot.clock_s, age_s=None, ego_lane_index=None,
                             mio_id=None, forward_mio_id=None, objects=[])
    return SceneResponse(
        vehicle_id=vehicle_id, clock_s=snapshot.clock_s, age_s=age_s,
        ego_lane_index=scene.ego_lane_index if scene.ego_lane_index >= 0 else None,
        mio_id=scene.mio_id if scene.has_mio else None,
        forward_mio_id=scene.forward_mio_id if scene.has_forward_mio else None,
        objects=[_object_view(obj, scene) for obj in scene.objects])


def planner_view(snapshot: StoreSnapshot, vehicle_id: str, graph_mermaid: str | None) -> PlannerResponse:
    state, age_s = _latest(snapshot, "planner/state")
    if state is None:
        return PlannerResponse(vehicle_id=vehicle_id, clock_s=snapshot.clock_s, age_s=None, scenario=None,
                               machine=None, state=None, time_in_state_s=None, recent_transitions=[],
                               graph_mermaid=graph_mermaid)
    transitions = [TransitionView(time_s=t.time_s, from_state=t.from_state, to_state=t.to_state, event=t.event,
                                  reason=t.reason, forced=t.forced) for t in state.recent_transitions]
    return PlannerResponse(
        vehicle_id=vehicle_id, clock_s=snapshot.clock_s, age_s=age_s,
        scenario=enum_label(planner_pb2.Scenario, state.scenario), machine=state.machine, state=state.state,
        time_in_state_s=state.time_in_state_s, recent_transitions=transitions,
        graph_mermaid=state.graph_mermaid or graph_mermaid)


def forward_gap_m(scene: scene_pb2.Scene | None) -> float | None:
    if scene is None or not scene.has_forward_mio:
        return None
    for obj in scene.objects:
        if obj.object_id == scene.forward_mio_id:
            return obj.longitudinal_gap_m
    return None


def time_gap_s(gap_m: float | None, speed_mps: float | None) -> float | None:
    if gap_m is None or speed_mps is None or speed_mps < MIN_SPEED_FOR_TIME_GAP_MPS:
        return None
    return gap_m / speed_mps


def _size(prop, default_m: float) -> float:
    return prop.value if prop.confidence != UNKNOWN_CONFIDENCE and prop.value > 0 else default_m


def _live_objects(scene: scene_pb2.Scene | None, ego) -> list[LiveObject]:
    if scene is None:
        return []
    ex, ey, eh = (ego.x_m, ego.y_m, ego.heading_rad) if ego is not None else (0.0, 0.0, 0.0)
    cos_h, sin_h = math.cos(-eh), math.sin(-eh)
    objects = []
    for obj in scene.objects:
        p = obj.position
        if p.confidence == UNKNOWN_CONFIDENCE:
            continue
        dx, dy = p.x_m - ex, p.y_m - ey
        heading = obj.heading_rad.value - eh if obj.heading_rad.confidence != UNKNOWN_CONFIDENCE else 0.0
        station = obj.station_id
        objects.append(LiveObject(
            id=obj.object_id, x_m=dx * cos_h - dy * sin_h, y_m=dx * sin_h + dy * cos_h, heading_rad=heading,
            length_m=_size(obj.length_m, DEFAULT_LENGTH_M), width_m=_size(obj.width_m, DEFAULT_WIDTH_M),
            confidence=max(0.0, p.confidence), object_class=enum_label(sensors_pb2.ObjectClass, obj.object_class),
            station_id=station.value if station.confidence != UNKNOWN_CONFIDENCE and station.value else None,
            forward_mio=scene.has_forward_mio and obj.object_id == scene.forward_mio_id, v2v_trust=obj.v2v_trust))
    return objects


def live_frame(snapshot: StoreSnapshot, seq: int, alive: dict[str, bool]) -> LiveFrame:
    ego, _ = _latest(snapshot, "ego/state")
    scene, _ = _latest(snapshot, "scene")
    v2x, _ = _latest(snapshot, "v2x/status")
    planner, _ = _latest(snapshot, "planner/state")
    actuation, _ = _latest(snapshot, "actuation/status")
    speed = ego.speed_mps if ego is not None else None
    gap = forward_gap_m(scene)
    lane = ego.lane if ego is not None else None
    trust = scene_trust(snapshot)
    return LiveFrame(
        seq=seq, clock_s=snapshot.clock_s, speed_mps=speed, accel_mps2=ego.accel_mps2 if ego is not None else None,
        gap_m=gap, time_gap_s=time_gap_s(gap, speed),
        lane_width_m=lane.lane_width_m if lane is not None and lane.lane_width_m > 0 else DEFAULT_LANE_WIDTH_M,
        ego_lane_index=scene.ego_lane_index if scene is not None and scene.ego_lane_index >= 0 else None,
        lateral_offset_m=lane.lateral_offset_m if lane is not None and lane.matched else 0.0,
        objects=_live_objects(scene, ego),
        stations=[LiveStation(station_id=s.station_id, state=_station_link(s),
                              trust=trust.get(s.station_id, s.trust), reception_ratio=s.reception_ratio,
                              signed=s.signed, verified=s.verified,
                              trusted=s.trusted, last_security_reason=s.last_security_reason)
                  for s in (v2x.stations if v2x else [])],
        scenario=enum_label(planner_pb2.Scenario, planner.scenario) if planner else None,
        planner_state=planner.state if planner else None,
        time_in_state_s=planner.time_in_state_s if planner else None,
        mode=enum_label(actuation_pb2.DrivingMode, actuation.mode) if actuation else None,
        mode_change_reason=actuation.last_mode_change_reason if actuation else "",
        availability=[LiveAvailability(mode=enum_label(actuation_pb2.DrivingMode, a.mode), available=a.available,
                                       unmet_condition=a.unmet_condition)
                      for a in (actuation.availability if actuation else [])],
        health=alive)
