"""From bus messages (used as plain data) to the controller inputs: targets and spacing.

The planner's BehaviourRequest names the targets; the Scene gives their gap and motion. The forward MIO is
always added as a predecessor even when the planner did not list it, so the emergency path and min-select
never ignore the vehicle directly ahead.

V2V freshness: a target's V2V age is the time since its latest CAM was measured (SceneObject.v2v_time_s), when
its acceleration is supported by SENSOR_SOURCE_V2V and not faded (confidence >= 0), else there is no V2V. The
scene keeps a V2V-supported property for its fade time (about a second), far beyond GCDC's 400 ms.

In path: a virtual target (the merge's partner in the other lane) is in our path only once the scene puts it in
our corridor (its MIO) or our lane (its forward MIO); until then the emergency path does not judge it, because a
longitudinal gap to a car a lane to the side is no time to collision (merge: a merger 2.5 m behind a slower
gap maker in the next lane emergency-braked at 6 m/s2, and the gap maker's follower braked for that).
"""

from __future__ import annotations

from coopdrive.roadmap.lane import lateral_offset_after_m
from coopdrive.v1 import ego_pb2, header_pb2, planner_pb2, scene_pb2

from .longitudinal.types import Spacing, Target

V2V = header_pb2.SENSOR_SOURCE_V2V
# Scene object ids count up from 1; the planner's stop line takes the one id they never reach.
STOP_LINE_OBJECT_ID = 2 ** 32 - 1
# Where a stop line target leaves the vehicle: this far before the line.
STOP_LINE_MARGIN_M = 1.0


def spacing_from_request(request: planner_pb2.BehaviourRequest) -> Spacing | None:
    """None when the request carries no spacing (the controller then uses the profile's)."""
    if not request.HasField("spacing"):
        return None
    return Spacing(request.spacing.standstill_m, request.spacing.time_gap_s)


def _target(obj: scene_pb2.SceneObject, role: int, extra_gap_m: float, now_s: float, in_path: bool) -> Target:
    accel = obj.accel_mps2
    has_v2v = accel.confidence >= 0 and V2V in accel.sources and obj.v2v_time_s > 0
    intended = obj.intended_accel_mps2
    return Target(
        object_id=obj.object_id,
        gap_m=obj.longitudinal_gap_m,
        speed_mps=obj.speed_mps.value,
        accel_mps2=accel.value if has_v2v else None,
        v2v_age_s=max(now_s - obj.v2v_time_s, 0.0) if has_v2v else None,
        role=role,
        extra_gap_m=extra_gap_m,
        intended_accel_mps2=intended.value if V2V in intended.sources else None,
        in_path=in_path,
    )


def targets_from_scene(request: planner_pb2.BehaviourRequest, scene: scene_pb2.Scene, now_s: float,
                       ego_speed_mps: float = 0.0) -> list[Target]:
    """Targets ahead of the ego (gap > 0) that the scene knows, unknown ids left out, and the stop line."""
    objects = {o.object_id: o for o in scene.objects if not o.ghost}
    in_our_path = {object_id for has, object_id in ((scene.has_mio, scene.mio_id),
                                                   (scene.has_forward_mio, scene.forward_mio_id)) if has}
    targets: dict[int, Target] = {}
    for tv in request.targets:
        obj = objects.get(tv.object_id)
        if obj is not None and obj.longitudinal_gap_m > 0:
            in_path = tv.role != planner_pb2.TARGET_ROLE_VIRTUAL or obj.object_id in in_our_path
            targets[obj.object_id] = _target(obj, tv.role, tv.extra_gap_m, now_s, in_path)
    if scene.has_forward_mio and scene.forward_mio_id not in targets:
        obj = objects.get(scene.forward_mio_id)
        if obj is not None and obj.longitudinal_gap_m > 0:
            targets[obj.object_id] = _target(obj, planner_pb2.TARGET_ROLE_PREDECESSOR, 0.0, now_s, True)
    stop_line = stop_line_target(request, ego_speed_mps, now_s)
    if stop_line is not None:
        targets[stop_line.object_id] = stop_line
    return list(targets.values())


def stop_line_target(request: planner_pb2.BehaviourRequest, ego_speed_mps: float, now_s: float) -> Target | None:
    """A hard stop line (give way, road works ahead) as a target whose gap is the distance to the point
    STOP_LINE_MARGIN_M before the line. The planner measured the distance at its own, slower rate; the ego
    has moved on since."""
    if not request.has_stop_line:
        return None
    age_s = max(0.0, now_s - request.header.sample_time_s)
    gap_m = request.stop_line_distance_m - ego_speed_mps * age_s
    return Target(object_id=STOP_LINE_OBJECT_ID, gap_m=gap_m - STOP_LINE_MARGIN_M, speed_mps=0.0,
                  role=planner_pb2.TARGET_ROLE_YIELD, stop_line=True)


CAMERA_LANE_SOURCES = (scene_pb2.LANE_SOURCE_FUSED, scene_pb2.LANE_SOURCE_CAMERA)


def lane_for_steering(ego: ego_pb2.EgoState, scene: scene_pb2.Scene | None, now_s: float,
                      max_age_s: float) -> ego_pb2.LanePosition:
    """The lane to steer in: the scene's when it comes from the camera (fused with the map, or alone where the
    map at the estimated position disagrees) and is fresh, moved on to now_s along its heading error; otherwise
    the map's lane at the estimated position. Its index and offset change together when the camera sees the car
    cross a line, so the offset to the target lane stays continuous."""
    if scene is None or not scene.ego_lane.valid or scene.ego_lane.source not in CAMERA_LANE_SOURCES:
        return ego.lane
    age_s = now_s - scene.header.sample_time_s
    if not 0.0 <= age_s <= max_age_s:
        return ego.lane
    seen = scene.ego_lane
    lane = ego_pb2.LanePosition(matched=True, lane_index=seen.lane_index, lane_width_m=seen.lane_width_m,
                                heading_error_rad=seen.heading_error_rad, curvature_1pm=seen.curvature_1pm)
    lane.lateral_offset_m = lateral_offset_after_m(seen.lateral_offset_m, ego.speed_mps, seen.heading_error_rad, age_s)
    return lane


def offset_to_target_lane_m(lane: ego_pb2.LanePosition, request: planner_pb2.BehaviourRequest) -> float:
    """The ego's lateral offset from the centre of the lane the planner wants (positive left).

    Lanes count up to the left, so a target lane one to the right has its centre one lane width to the right:
    the offset grows by that width, and the lateral controller sees the jump as the start of a lane change
    (Heudiasyc's reference switch). When the ego crosses the line, the matched lane and its offset change
    together and the offset to the target lane stays continuous.
    """
    if request.target_lane_index < 0:
        return lane.lateral_offset_m
    lanes_to_go = request.target_lane_index - lane.lane_index
    return lane.lateral_offset_m - lanes_to_go * lane.lane_width_m
