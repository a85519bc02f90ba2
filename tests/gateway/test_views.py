"""Views and live frames from a store snapshot, without any network."""

import pytest

from coopdrive.services.gateway.state_store import StateStore
from coopdrive.services.gateway.views import enum_label, live_frame, scene_view, time_gap_s
from coopdrive.v1 import actuation_pb2, ego_pb2, scene_pb2, sensors_pb2

HALF_PI = 1.5707963267948966


def store_with(**messages) -> StateStore:
    topics = {"ego": "ego/state", "scene": "scene", "actuation": "actuation/status"}
    store = StateStore(["geolocation", "scene", "actuation"], rate_window_s=5.0)
    publishers = {"ego": "geolocation", "scene": "scene", "actuation": "actuation"}
    for name, message in messages.items():
        store.record(publishers[name], topics[name], message, 1.0, wall_s=1.0)
    store.note_clock(1.0)
    return store


def scene_with_lead(x_m: float, y_m: float, confidence: float = 0.9) -> scene_pb2.Scene:
    scene = scene_pb2.Scene(has_forward_mio=True, forward_mio_id=3, ego_lane_index=-1)
    lead = scene.objects.add(object_id=3, longitudinal_gap_m=25.0)
    lead.position.x_m, lead.position.y_m, lead.position.confidence = x_m, y_m, confidence
    lead.heading_rad.value, lead.heading_rad.confidence = HALF_PI, 0.5
    lead.length_m.confidence = -1.0
    return scene


def test_enum_labels_drop_the_type_prefix():
    assert enum_label(sensors_pb2.ObjectClass, sensors_pb2.OBJECT_CLASS_EMERGENCY_VEHICLE) == "emergency_vehicle"
    assert enum_label(actuation_pb2.DrivingMode, actuation_pb2.DRIVING_MODE_SAFE_STOP) == "safe_stop"


def test_live_objects_are_placed_in_the_ego_frame_ahead_and_left():
    ego = ego_pb2.EgoState(x_m=10.0, y_m=20.0, heading_rad=HALF_PI, speed_mps=10.0)  # heading north
    frame = live_frame(store_with(ego=ego, scene=scene_with_lead(9.0, 50.0)).snapshot(1.0), 1, {})
    [lead] = frame.objects
    assert lead.x_m == pytest.approx(30.0) and lead.y_m == pytest.approx(1.0)  # 30 m ahead, 1 m to the left
    assert lead.heading_rad == pytest.approx(0.0)
    assert lead.length_m == 4.5  # unknown: drawn as a passenger car
    assert lead.forward_mio and lead.confidence == 0.9


def test_the_live_frame_carries_gap_time_gap_and_why_a_mode_is_unavailable():
    actuation = actuation_pb2.ActuationStatus(mode=actuation_pb2.DRIVING_MODE_MANUAL)
    actuation.availability.add(mode=actuation_pb2.DRIVING_MODE_AUTONOMOUS, unmet_condition="no lane match")
    store = store_with(ego=ego_pb2.EgoState(speed_mps=12.5), scene=scene_with_lead(30.0, 0.0), actuation=actuation)
    frame = live_frame(store.snapshot(1.0), 7, {"scene": True})
    assert (frame.seq, frame.gap_m, frame.time_gap_s) == (7, 25.0, 2.0)
    assert frame.mode == "manual"
    assert frame.availability[0].model_dump() == {"mode": "autonomous", "available": False,
                                                  "unmet_condition": "no lane match"}
    assert frame.ego_lane_index is None  # -1: not matched to a map
    assert frame.health == {"scene": True}


def test_objects_whose_position_has_faded_are_not_drawn_but_stay_in_the_scene_view():
    store = store_with(scene=scene_with_lead(30.0, 0.0, confidence=-1.0))
    assert live_frame(store.snapshot(1.0), 1, {}).objects == []
    [lead] = scene_view(store.snapshot(1.0), "ego").objects
    assert lead.position.x_m is None and lead.position.confidence is None


def test_there_is_no_time_gap_without_a_gap_or_when_standing_still():
    assert time_gap_s(None, 10.0) is None
    assert time_gap_s(20.0, 0.1) is None
    assert time_gap_s(20.0, 10.0) == 2.0


def test_an_empty_store_gives_an_empty_frame():
    frame = live_frame(StateStore([], 1.0).snapshot(0.0), 1, {})
    assert frame.speed_mps is None and frame.gap_m is None and frame.objects == [] and frame.mode is None
