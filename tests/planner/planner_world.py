"""Hand-made planner inputs: ego, scene objects, iCLCMs, CAMs and DENMs as plain proto data."""

from __future__ import annotations

from coopdrive.services.planner.config import PlannerLogicConfig
from coopdrive.services.planner.inputs import PlannerInputs, Received
from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import ego_pb2, its_pb2, planner_pb2, scene_pb2

ME = 100
RSU = 900
DT_S = 0.1
ROADWORKS = 3
EMERGENCY_APPROACHING = 95


def ego(lane: int = 0, speed_mps: float = 15.0, x_m: float = 0.0, y_m: float = 0.0, heading_rad: float = 0.0,
        lateral_offset_m: float = 0.0, station_m: float = 0.0) -> ego_pb2.EgoState:
    e = ego_pb2.EgoState(x_m=x_m, y_m=y_m, heading_rad=heading_rad, speed_mps=speed_mps,
                         latitude_deg=50.0, longitude_deg=5.0)
    e.lane.matched = True
    e.lane.lane_index = lane
    e.lane.lateral_offset_m = lateral_offset_m
    e.lane.station_m = station_m
    return e


def obj(object_id: int, station: int = 0, gap_m: float = 20.0, lane: int = 0, x_m: float | None = None,
        y_m: float = 0.0, speed_mps: float = 15.0, heading_rad: float = 0.0) -> scene_pb2.SceneObject:
    o = scene_pb2.SceneObject(object_id=object_id, longitudinal_gap_m=gap_m)
    o.position.x_m = gap_m if x_m is None else x_m
    o.position.y_m = y_m
    o.speed_mps.value = speed_mps
    o.heading_rad.value = heading_rad
    o.lane_index.value = lane
    o.lane_index.confidence = 1.0
    o.station_id.value = station
    o.station_id.confidence = 1.0 if station else -1.0
    return o


def scene(*objects: scene_pb2.SceneObject, forward_mio: int | None = None, ego_lane: int = 0,
          neighbours: dict[int, tuple[int | None, int | None]] | None = None) -> scene_pb2.Scene:
    s = scene_pb2.Scene(objects=list(objects), ego_lane_index=ego_lane)
    if forward_mio is not None:
        s.has_forward_mio, s.forward_mio_id = True, forward_mio
    for offset, (ahead, behind) in (neighbours or {}).items():
        n = s.neighbours.add(lane_offset=offset)
        if ahead is not None:
            n.has_ahead, n.ahead_object_id = True, ahead
        if behind is not None:
            n.has_behind, n.behind_object_id = True, behind
    return s


def iclcm(station: int, at_s: float, **fields) -> Received:
    return Received(its_pb2.IclcmContent(station_id=station, **fields), at_s)


def rsu_start(at_s: float = 0.0) -> Received:
    return iclcm(RSU, at_s, has_low_frequency=True, start_platoon=its_pb2.START_PLATOON_B_AT_60_KPH)


def rsu_end(at_s: float = 0.0) -> Received:
    return iclcm(RSU, at_s, has_low_frequency=True, end_of_scenario=True)


def denm(cause: int, at_s: float = 0.0, origin: int = RSU, sequence: int = 1,
         metres_east: float | None = None) -> Received:
    """A DENM; with metres_east its event lies that far east of the ego() position."""
    d = its_pb2.DenmContent(station_id=origin, originating_station_id=origin, sequence_number=sequence,
                            validity_duration_s=600.0)
    d.situation.event_type.cause_code = cause
    if metres_east is not None:
        d.event_position.latitude_deg = 50.0
        d.event_position.longitude_deg = 5.0 + metres_east / (111_195.0 * 0.6427876)
    return Received(d, at_s)


def emergency_cam(station: int, at_s: float, metres_east: float) -> Received:
    c = its_pb2.CamContent(station_id=station, station_type=its_pb2.STATION_TYPE_SPECIAL_VEHICLES)
    c.reference_position.latitude_deg = 50.0
    c.reference_position.longitude_deg = 5.0 + metres_east / (111_195.0 * 0.6427876)
    c.low_frequency.vehicle_role = its_pb2.VEHICLE_ROLE_EMERGENCY
    return Received(c, at_s)


def inputs(scenario: int, **kwargs) -> PlannerInputs:
    return PlannerInputs(station_id=ME, scenario=scenario, **kwargs)


def planner(**overrides) -> Planner:
    return Planner(PlannerLogicConfig(**overrides))


def transitions(state: planner_pb2.PlannerState) -> list[tuple[str, str]]:
    return [(t.from_state, t.to_state) for t in state.recent_transitions]
