"""Bus messages to controller inputs, and the service configuration."""

import math

import pytest
from pydantic import ValidationError

from coopdrive.services.control.config import ControlConfig
from coopdrive.services.control.inputs import (lane_for_steering, offset_to_target_lane_m, spacing_from_request,
                                              targets_from_scene)
from coopdrive.services.control.longitudinal import CaccLaw
from coopdrive.services.control.profiles import CAR, TRUCK, profile_by_name
from coopdrive.v1 import ego_pb2, header_pb2, planner_pb2, scene_pb2
from coopdrive.vehicle import TRUCK as TRUCK_VEHICLE


def scene_object(object_id, gap_m, speed_mps, accel_mps2=None, v2v=True, v2v_time_s=10.0):
    obj = scene_pb2.SceneObject(object_id=object_id, longitudinal_gap_m=gap_m)
    if v2v and accel_mps2 is not None:
        obj.v2v_time_s = v2v_time_s
    obj.speed_mps.value = speed_mps
    if accel_mps2 is not None:
        obj.accel_mps2.value = accel_mps2
        obj.accel_mps2.confidence = 0.9
        obj.accel_mps2.sources.append(header_pb2.SENSOR_SOURCE_V2V if v2v else header_pb2.SENSOR_SOURCE_RADAR)
    return obj


def test_planner_targets_take_gap_and_motion_from_the_scene_and_v2v_age_from_the_latest_cam():
    scene = scene_pb2.Scene(objects=[scene_object(4, 20.0, 21.0, 0.3, v2v_time_s=10.0)])
    scene.header.sample_time_s = 10.04
    request = planner_pb2.BehaviourRequest(targets=[planner_pb2.TargetVehicle(object_id=4, role=planner_pb2.TARGET_ROLE_VIRTUAL, extra_gap_m=2.0)])
    (t,) = targets_from_scene(request, scene, now_s=10.05)
    assert (t.object_id, t.gap_m, t.speed_mps, t.accel_mps2, t.role, t.extra_gap_m) == (4, 20.0, 21.0, 0.3, planner_pb2.TARGET_ROLE_VIRTUAL, 2.0)
    assert t.v2v_age_s == pytest.approx(0.05)


def test_the_v2v_age_is_the_time_since_the_latest_cam_however_fresh_the_scene_is():
    # The scene still carries a V2V-supported acceleration (it fades over a second), but the CAM is 0.6 s old.
    scene = scene_pb2.Scene(objects=[scene_object(4, 20.0, 21.0, 0.3, v2v_time_s=9.4)])
    scene.header.sample_time_s = 10.0
    (t,) = targets_from_scene(planner_pb2.BehaviourRequest(targets=[planner_pb2.TargetVehicle(object_id=4)]),
                              scene, now_s=10.0)
    assert t.v2v_age_s == pytest.approx(0.6)


def test_an_acceleration_without_v2v_support_is_not_used_as_feedforward():
    scene = scene_pb2.Scene(objects=[scene_object(4, 20.0, 21.0, 0.3, v2v=False)])
    request = planner_pb2.BehaviourRequest(targets=[planner_pb2.TargetVehicle(object_id=4)])
    (t,) = targets_from_scene(request, scene, now_s=0.0)
    assert t.accel_mps2 is None and t.v2v_age_s is None


def test_the_acceleration_a_station_requests_reaches_the_target_only_when_the_scene_put_it_there():
    requesting = scene_object(4, 20.0, 21.0, 0.3)
    requesting.intended_accel_mps2.value = -5.0
    requesting.intended_accel_mps2.sources.append(header_pb2.SENSOR_SOURCE_V2V)
    silent = scene_object(5, 40.0, 21.0, 0.3)
    scene = scene_pb2.Scene(objects=[requesting, silent])
    request = planner_pb2.BehaviourRequest(targets=[planner_pb2.TargetVehicle(object_id=4),
                                                    planner_pb2.TargetVehicle(object_id=5)])
    assert [t.intended_accel_mps2 for t in targets_from_scene(request, scene, now_s=0.0)] == [-5.0, None]


def test_the_forward_mio_is_always_a_target_and_vehicles_behind_are_not():
    scene = scene_pb2.Scene(objects=[scene_object(1, 15.0, 20.0), scene_object(2, -8.0, 20.0)], has_forward_mio=True, forward_mio_id=1)
    request = planner_pb2.BehaviourRequest(targets=[planner_pb2.TargetVehicle(object_id=2)])
    targets = targets_from_scene(request, scene, now_s=0.0)
    assert [(t.object_id, t.role) for t in targets] == [(1, planner_pb2.TARGET_ROLE_PREDECESSOR)]


def test_a_virtual_target_is_in_our_path_only_once_the_scene_puts_it_in_our_corridor_or_lane():
    beside = scene_object(3, 2.5, 16.7)
    request = planner_pb2.BehaviourRequest(targets=[
        planner_pb2.TargetVehicle(object_id=3, role=planner_pb2.TARGET_ROLE_VIRTUAL),
        planner_pb2.TargetVehicle(object_id=5, role=planner_pb2.TARGET_ROLE_PREDECESSOR)])
    other_lane = scene_pb2.Scene(objects=[beside, scene_object(5, 30.0, 16.7)])
    assert [(t.object_id, t.in_path) for t in targets_from_scene(request, other_lane, now_s=0.0)] == [(3, False), (5, True)]
    for in_corridor in (dict(has_mio=True, mio_id=3), dict(has_forward_mio=True, forward_mio_id=3)):
        cutting_in = scene_pb2.Scene(objects=[beside, scene_object(5, 30.0, 16.7)], **in_corridor)
        assert all(t.in_path for t in targets_from_scene(request, cutting_in, now_s=0.0))


def test_the_spacing_comes_from_the_request_when_present():
    assert spacing_from_request(planner_pb2.BehaviourRequest()) is None
    request = planner_pb2.BehaviourRequest(spacing=planner_pb2.SpacingPolicy(standstill_m=6.0, time_gap_s=0.8))
    assert spacing_from_request(request).time_gap_s == pytest.approx(0.8)


def test_the_config_selects_profile_laws_and_top_level_overrides():
    config = ControlConfig(vehicle="truck", cacc_law="ploeg",
                           profile_overrides={"vehicle": {"response_time_constant_s": 0.4}})
    assert config.cacc_law is CaccLaw.PLOEG
    profile = config.vehicle_profile()
    assert profile.engine_lag_s == 0.4 and profile.vehicle.mass_kg == TRUCK.vehicle.mass_kg
    assert profile.wheelbase_m == TRUCK_VEHICLE.wheelbase_m


def test_the_config_rejects_unknown_fields_and_profiles():
    with pytest.raises(ValidationError):
        ControlConfig(rate_hz=50)
    with pytest.raises(ValueError, match="unknown vehicle profile"):
        profile_by_name("bus")


def test_profiles_forbid_unknown_fields_and_carry_units():
    with pytest.raises(ValidationError):
        CAR.model_validate({**CAR.model_dump(), "lag": 0.3})
    assert TRUCK.limits.max_accel_mps2 < CAR.limits.max_accel_mps2


def lane_position(lane_index, offset_m, width_m=3.5):
    return ego_pb2.LanePosition(matched=True, lane_index=lane_index, lateral_offset_m=offset_m, lane_width_m=width_m)


def test_a_target_lane_to_the_right_puts_the_ego_one_lane_width_left_of_its_centre():
    request = planner_pb2.BehaviourRequest(target_lane_index=0)
    assert offset_to_target_lane_m(lane_position(1, 0.2), request) == pytest.approx(3.7)


def test_the_offset_to_the_target_lane_stays_continuous_when_the_ego_crosses_the_line():
    request = planner_pb2.BehaviourRequest(target_lane_index=0)
    before = offset_to_target_lane_m(lane_position(1, -1.74), request)
    after = offset_to_target_lane_m(lane_position(0, 1.76), request)
    assert before == pytest.approx(after, abs=0.05)


def test_without_a_target_lane_the_offset_is_to_the_lane_the_ego_is_in():
    request = planner_pb2.BehaviourRequest(target_lane_index=-1)
    assert offset_to_target_lane_m(lane_position(1, 0.3), request) == pytest.approx(0.3)


def _scene_with_lane(source: int, time_s: float = 1.0) -> scene_pb2.Scene:
    scene = scene_pb2.Scene()
    scene.header.sample_time_s = time_s
    lane = scene.ego_lane
    lane.valid, lane.source, lane.lane_index = True, source, 2
    lane.lateral_offset_m, lane.heading_error_rad, lane.lane_width_m = 0.1, 0.01, 3.5
    return scene


def test_steering_takes_the_scene_s_camera_lane_while_fresh_moved_on_along_its_heading_error():
    ego = ego_pb2.EgoState(speed_mps=20.0)
    ego.lane.matched, ego.lane.lane_index, ego.lane.lateral_offset_m = True, 1, 1.4
    lane = lane_for_steering(ego, _scene_with_lane(scene_pb2.LANE_SOURCE_CAMERA), 1.05, max_age_s=0.1)
    assert lane.matched and lane.lane_index == 2
    assert lane.lateral_offset_m == pytest.approx(0.1 + 20.0 * math.sin(0.01) * 0.05)
    fused = lane_for_steering(ego, _scene_with_lane(scene_pb2.LANE_SOURCE_FUSED), 1.0, max_age_s=0.1)
    assert fused.lateral_offset_m == pytest.approx(0.1)


def test_steering_keeps_the_map_lane_when_the_scene_s_lane_is_the_map_s_stale_or_missing():
    ego = ego_pb2.EgoState(speed_mps=20.0)
    ego.lane.matched, ego.lane.lane_index, ego.lane.lateral_offset_m = True, 1, 1.4
    for scene, now_s in ((None, 1.0), (_scene_with_lane(scene_pb2.LANE_SOURCE_MAP), 1.0),
                         (_scene_with_lane(scene_pb2.LANE_SOURCE_CAMERA), 1.2), (scene_pb2.Scene(), 1.0)):
        assert lane_for_steering(ego, scene, now_s, max_age_s=0.1) == ego.lane
