"""Building BehaviourRequests: the safe default (keep lane, follow the MIO) and its additions."""

from __future__ import annotations

from coopdrive.v1 import planner_pb2, scene_pb2

from .situation import Situation


def keep_lane(sit: Situation, speed_mps: float, time_gap_s: float, lane_index: int | None = None
              ) -> planner_pb2.BehaviourRequest:
    """Keep (or go to) a lane at a speed, with the vehicle directly ahead as predecessor."""
    request = planner_pb2.BehaviourRequest(
        target_lane_index=sit.ego_lane() if lane_index is None else lane_index,
        desired_speed_mps=speed_mps)
    request.header.sample_time_s = sit.now_s
    request.spacing.standstill_m = sit.config.standstill_m
    request.spacing.time_gap_s = time_gap_s
    mio = sit.forward_mio()
    if mio is not None:
        add_target(request, mio, planner_pb2.TARGET_ROLE_PREDECESSOR)
    return request


def add_target(request: planner_pb2.BehaviourRequest, obj: scene_pb2.SceneObject | None, role: int,
               extra_gap_m: float = 0.0) -> None:
    """Adds a scene object as a target once (a later role for the same object is ignored)."""
    if obj is None or any(t.object_id == obj.object_id for t in request.targets):
        return
    request.targets.add(object_id=obj.object_id, station_id=Situation.station_of(obj), role=role,
                        extra_gap_m=extra_gap_m)


def spacing_m(sit: Situation, time_gap_s: float) -> float:
    # (eq. 4) Heudiasyc spacing d = r + h v
    return sit.config.standstill_m + time_gap_s * sit.ego_speed_mps()
