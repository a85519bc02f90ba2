"""Signalised-intersection metrics from ground truth: red-light violations (red, red-amber, and a red that came
between two samples), stops per crossing, time lost against free flow, the sum of positive acceleration, and the
margin to the end of amber, on trajectories whose answers are known in closed form."""

import pytest

from coopdrive.services.sim.mission_verdict import MissionJudge
from coopdrive.services.sim.scenario_config import parse_scenario
from coopdrive.services.sim.signal_metrics import signal_metrics
from coopdrive.v1 import sim_pb2
from tests.sim.signal_truth import AMBER, GREEN, RED, RED_AMBER, SAMPLE_S, frames, light, steady

GREEN_TILL_40 = light([(RED, 0, 10), (RED_AMBER, 10, 11), (GREEN, 11, 40), (AMBER, 40, 43), (RED, 43, 1e9)])


def test_a_car_crossing_on_green_at_a_steady_speed_loses_no_time_and_stops_nowhere():
    metrics = signal_metrics(frames(steady(10.0, 30.03), GREEN_TILL_40, 60.0), {"car1"})
    assert (metrics["signal_red_light_violations"], metrics["signal_crossings"],
            metrics["signal_stops_per_crossing"]) == (0, 1, 0)
    assert metrics["signal_time_lost_s"] == pytest.approx(0.0, abs=1e-6)
    assert metrics["signal_positive_accel_mps"] == pytest.approx(0.0)
    assert metrics["signal_min_amber_margin_s"] == pytest.approx(43.0 - 30.03, abs=1e-6)


def test_crossing_on_red_on_red_amber_and_after_the_amber_ran_out_are_each_a_violation():
    for crossing_s in (5.0, 10.5, 43.05):
        metrics = signal_metrics(frames(steady(10.0, crossing_s), GREEN_TILL_40, 60.0), {"car1"})
        assert metrics["signal_red_light_violations"] == 1, crossing_s


def test_a_scripted_cars_violation_is_counted_apart_from_the_stacks():
    metrics = signal_metrics(frames(steady(10.0, 5.0), GREEN_TILL_40, 30.0, "bus"), {"car1"})
    assert (metrics["signal_red_light_violations"], metrics["signal_red_light_violations_scripted"],
            metrics["signal_crossings"]) == (0, 1, 0)


def stop_and_go(t):
    """10 m/s, braking at 2 m/s2 from t = 10 s to stand 1 m before the line at 15 s, waiting until 25 s, then
    starting at 2 m/s2 back to 10 m/s."""
    if t < 10.0:
        return -1.0 - 25.0 - 10.0 * (10.0 - t), 10.0
    if t < 15.0:
        return -1.0 - (15.0 - t) ** 2, 2.0 * (15.0 - t)
    if t < 25.0:
        return -1.0, 0.0
    if t < 30.0:
        return -1.0 + (t - 25.0) ** 2, 2.0 * (t - 25.0)
    return -1.0 + 25.0 + 10.0 * (t - 30.0), 10.0


def test_a_stop_at_red_counts_one_stop_and_loses_the_wait_and_half_of_each_speed_change():
    metrics = signal_metrics(frames(stop_and_go, light([(RED, 0, 24), (RED_AMBER, 24, 25), (GREEN, 25, 60),
                                                        (AMBER, 60, 63), (RED, 63, 1e9)]), 50.0, start_s=-20.0),
                             {"car1"})
    assert (metrics["signal_red_light_violations"], metrics["signal_stops_per_crossing"]) == (0, 1)
    # Braking from 10 m/s at 2 m/s2 takes 5 s over 25 m (2.5 s at 10 m/s), starting again as long: 2.5 + 10 + 2.5.
    assert metrics["signal_time_lost_s"] == pytest.approx(15.0, abs=0.05)
    assert metrics["signal_positive_accel_mps"] == pytest.approx(10.0, abs=1e-6)


def test_a_world_without_traffic_lights_has_no_signal_figures():
    assert signal_metrics([(0.0, [], [])], {"car1"}) == {}


def test_a_stack_crossing_on_red_fails_the_run_and_the_verdict_names_it():
    config = parse_scenario({"name": "signals", "duration_s": 30, "vehicles": [
        {"vehicle_id": "car1", "station_id": 1, "lane": 0, "station_m": 0, "speed_mps": 10}]})
    judge = MissionJudge(config, ["car1"])
    for time_s, vehicles, signals in frames(steady(10.0, 5.0), GREEN_TILL_40, 30.0):
        judge.observe(time_s, sim_pb2.GroundTruth(vehicles=vehicles, signals=signals))
    assert judge.verdict() == (False, "red-light violation: car1 at 5.0 s (intersection 7, group 2)")
    assert judge.metrics()["signal_red_light_violations"] == 1
