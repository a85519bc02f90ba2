"""The scene's tracking figures, on a hand-built run: truth at 10 Hz, one observer's scenes at 20 Hz."""

import pytest

from coopdrive.judging.run_messages import RunMessages
from coopdrive.judging.score import ASSOCIATION_GATE_M
from coopdrive.judging.tracking import tracking_metrics
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import scene_pb2
from tests.judging.synthetic import REAR_OVERHANG_M, truth_at

DURATION_S = 2.0
SCENE_STEP_S = 0.05


def leader_x(t):
    return 30.0 + 10.0 * t


def far_x(t):
    """A third car 100 m ahead of the observer: out of tracking range, nobody expects an object for it."""
    return 100.0 + 12.0 * t


def run(objects_at):
    """objects_at(t) -> [(object_id, x_m, y_m)] seen by the observer, which drives at x = 12 t (x_m None: the
    object's position has faded)."""
    messages = RunMessages()
    for k in range(round(DURATION_S / 0.1) + 1):
        t = k * 0.1
        messages.add("coopdrive/world/ground_truth", truth_at(t, [
            dict(vehicle_id="leader", x_m=leader_x(t), y_m=0.0, speed_mps=10.0),
            dict(vehicle_id="observer", x_m=12.0 * t, y_m=0.0, speed_mps=12.0, automated=True),
            dict(vehicle_id="far", x_m=far_x(t), y_m=0.0, speed_mps=12.0)]))
    for k in range(round(DURATION_S / SCENE_STEP_S) + 1):
        t = k * SCENE_STEP_S
        scene = scene_pb2.Scene()
        scene.header.sample_time_s = t
        for object_id, x_m, y_m in objects_at(t):
            obj = scene.objects.add(object_id=object_id)
            if x_m is None:
                obj.position.confidence = -1.0  # faded: the scene leaves the position out
            else:
                obj.position.x_m, obj.position.y_m = x_m, y_m
        messages.add("coopdrive/observer/scene", scene)
    return tracking_metrics(TruthSeries.from_ground_truth(messages.sorted_truth()), messages, ASSOCIATION_GATE_M)


def leader_rear_x(t):
    return leader_x(t) - REAR_OVERHANG_M


def test_errors_are_measured_at_the_rear_bumper_and_the_95th_percentile_is_reported():
    # 0.2 m behind the true rear bumper, except 0.8 m for the first tenth of the run.
    metrics = run(lambda t: [(7, leader_rear_x(t) - (0.8 if t < 0.2 else 0.2), 0.0)])
    assert metrics["object_position_error_p95_m"] == pytest.approx(0.8)
    assert metrics["object_coverage_ratio"] == 1.0
    assert metrics["false_object_max_s"] == 0.0
    assert metrics["id_switches"] == 0


def test_a_vehicle_in_range_without_an_object_lowers_the_coverage():
    metrics = run(lambda t: [(7, leader_rear_x(t), 0.0)] if t < 1.0 else [])
    assert metrics["object_coverage_ratio"] == pytest.approx(20 / 41)


def test_an_object_near_no_vehicle_is_false_for_as_long_as_it_stays():
    def objects(t):
        seen = [(7, leader_rear_x(t), 0.0)]
        if 0.49 < t < 1.21:
            seen.append((12, 12.0 * t + 15.0, 6.0))  # 6 m to the side of the empty road
        return seen

    assert run(objects)["false_object_max_s"] == pytest.approx(0.7)


def test_an_object_on_the_side_of_a_vehicle_is_not_false_even_far_from_its_rear_bumper():
    # The nearest face of a car beside us: its flank, 3 m ahead of its rear bumper.
    metrics = run(lambda t: [(7, leader_rear_x(t) + 3.0, 0.9)])
    assert metrics["false_object_max_s"] == 0.0
    assert metrics["object_coverage_ratio"] == 0.0  # 3 m off the reference point is no track of it


def test_a_new_object_id_for_the_same_vehicle_is_an_identity_switch_counted_per_10_minutes():
    metrics = run(lambda t: [(7 if t < 1.0 else 9, leader_rear_x(t), 0.0)])
    assert metrics["id_switches"] == 1
    # One tracked vehicle over 2 s: one switch is 300 per vehicle per 10 minutes.
    assert metrics["id_switches_per_vehicle_per_10min"] == pytest.approx(300.0)


def test_without_scenes_there_is_nothing_to_report():
    messages = RunMessages()
    messages.add("coopdrive/world/ground_truth", truth_at(0.0, [dict(vehicle_id="a", x_m=0.0, y_m=0.0)]))
    assert tracking_metrics(TruthSeries.from_ground_truth(messages.sorted_truth()), messages, 3.0) == {}


def test_an_object_whose_position_faded_is_neither_a_track_nor_a_false_object():
    placed = run(lambda t: [(7, leader_rear_x(t), 0.0), (8, 0.0, 20.0)])
    assert placed["false_object_max_s"] == pytest.approx(DURATION_S)  # 20 m off the road: false all along
    faded = run(lambda t: [(7, leader_rear_x(t), 0.0), (8, None, None)])
    assert faded["false_object_max_s"] == 0.0
    assert faded["object_coverage_ratio"] == 1.0


def test_errors_beyond_the_gate_stay_in_the_percentile_and_are_counted():
    # 5 m behind the rear bumper (beyond the 3 m gate) for the first quarter second, 0.2 m after.
    metrics = run(lambda t: [(7, leader_rear_x(t) - (5.0 if t < 0.24 else 0.2), 0.0)])
    assert metrics["object_position_errors_beyond_gate"] == 5  # scenes at 0, 0.05, ..., 0.2 s
    assert metrics["object_position_error_p95_m"] == pytest.approx(5.0)
    assert metrics["object_coverage_ratio"] == pytest.approx(36 / 41)
