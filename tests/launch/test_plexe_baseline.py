"""The Plexe baseline: the string scenario's platoon under Plexe's PLOEG controller in SUMO (real libsumo)."""

import dataclasses
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest

from coopdrive.launch.baseline import BaselineComparison
from coopdrive.launch.plexe_baseline import (ACTIVE_CONTROLLER, CAR_FOLLOWING, PLOEG_KD, PLOEG_KP, PlexeString,
                                             run_plexe_string)
from coopdrive.launch.plexe_files import ROUTE_ID, SUMO_PLEXE, TYPE_ID, write_network, write_routes
from coopdrive.launch.scenario_source import resolve_scenario
from coopdrive.services.sim.string_gain import string_gains

# Plexe's ACC controller (CC_Const.h) and its fixed-acceleration record "1:a" (use it: 1, acceleration a).
ACC = 1
FIXED_ACCELERATION = CAR_FOLLOWING + "ccfa"
STEP_ACCEL_MPS2 = 1.0


@pytest.fixture(scope="module")
def string_setup() -> PlexeString:
    return PlexeString.of(resolve_scenario("string").config, duration_s=20.0)


@pytest.fixture(scope="module")
def string_run(string_setup):
    return run_plexe_string(string_setup)


def test_the_setup_takes_the_string_scenario_s_platoon_time_gap_and_driveline_lag(string_setup):
    config = resolve_scenario("string").config
    follower = next(v for v in config.vehicles if v.vehicle_id == config.judging.platoon[1])
    assert string_setup.vehicle_count == len(config.judging.platoon) == 9
    assert string_setup.vehicle_type.ploeg_h_s == config.judging.headway_s == 0.5
    assert string_setup.vehicle_type.engine_tau_s == follower.plant_profile().response_time_constant_s == 0.5
    assert (string_setup.vehicle_type.ploeg_kp, string_setup.vehicle_type.ploeg_kd) == (PLOEG_KP, PLOEG_KD)
    assert string_setup.step_s == config.step_s
    assert "PLOEG" in string_setup.description() and "engine lag 0.5 s" in string_setup.description()


def test_plexe_s_leader_drives_the_scenario_leader_s_speed_profile(string_setup, string_run):
    profile = [string_setup.leader_profile.speed_at(t) for t in string_run.time_s]
    assert np.max(np.abs(string_run.speeds_mps[0] - profile)) < 1e-6


def test_plexe_s_followers_gains_are_finite_and_measured_per_pair_as_the_judge_measures_ours(string_setup,
                                                                                            string_run):
    metrics = string_run.metrics(dataclasses.replace(string_setup, string_end_s=20.0))
    window = (string_run.time_s >= string_setup.string_start_s) & (string_run.time_s < 20.0)
    expected = string_gains([speeds[window] for speeds in string_run.speeds_mps], string_run.time_s[window],
                            string_setup.string_frequency_hz)
    pairs = [metrics[f"string_gain_pair_{index}"] for index in range(1, 9)]
    assert pairs == expected
    assert all(math.isfinite(gain) and 0.0 < gain < 2.0 for gain in pairs)
    assert metrics["string_gain"] == max(pairs)


def test_a_run_that_ends_inside_the_judged_window_has_no_string_gain(string_setup, string_run):
    assert string_setup.string_end_s == 40.0
    assert string_run.metrics(string_setup) == {}


def test_the_baseline_s_vehicles_keep_the_driveline_s_first_order_lag(string_setup):
    """A step in the requested acceleration: the vehicle's acceleration rises as 1 - (1 - alpha)^k, the first-order
    lag at tau discretised at the step (alpha = dt / (tau + dt)), and reaches 63 % at t = tau."""
    tau_s, step_s = string_setup.vehicle_type.engine_tau_s, string_setup.step_s
    accel = _fixed_acceleration_response(string_setup, steps=50)
    alpha = step_s / (tau_s + step_s)
    expected = STEP_ACCEL_MPS2 * (1.0 - (1.0 - alpha) ** np.arange(1, accel.size + 1))
    assert np.max(np.abs(accel - expected)) < 0.02
    at_tau = int(round(tau_s / step_s)) - 1
    assert accel[at_tau] == pytest.approx(STEP_ACCEL_MPS2 * (1.0 - math.exp(-1.0)), abs=0.02)


def _fixed_acceleration_response(setup: PlexeString, steps: int) -> np.ndarray:
    """One vehicle of the baseline's type, driving at a steady speed, asked for STEP_ACCEL_MPS2: its acceleration
    per step."""
    import libsumo

    with tempfile.TemporaryDirectory() as folder:
        network = write_network(Path(folder), 2000.0, setup.vehicle_type.max_speed_mps)
        routes = write_routes(Path(folder), setup.vehicle_type)
        libsumo.start(["sumo", "--net-file", str(network), "--route-files", str(routes), "--step-length",
                       str(setup.step_s), "--xml-validation", "never", "--no-step-log"])
        try:
            libsumo.vehicle.add("one", ROUTE_ID, typeID=TYPE_ID, departPos="100", departSpeed="20")
            libsumo.simulationStep()  # inserted, at its speed
            libsumo.vehicle.setSpeedMode("one", 0)
            libsumo.vehicle.setParameter("one", ACTIVE_CONTROLLER, str(ACC))
            libsumo.vehicle.setParameter("one", FIXED_ACCELERATION, f"1:{STEP_ACCEL_MPS2}")
            accel = []
            for _ in range(steps):
                libsumo.simulationStep()
                accel.append(libsumo.vehicle.getAcceleration("one"))
            return np.array(accel)
        finally:
            libsumo.close()


def test_the_comparison_lists_each_pair_s_gain_after_the_compared_metrics_leader_s_pair_first():
    ours = {"string_gain": 0.9, "string_gain_pair_2": 0.9, "string_gain_pair_10": 0.5, "string_gain_pair_1": 0.7,
            "min_gap_m": 12.0}
    plexe = {"string_gain": 0.8, "string_gain_pair_1": 0.8, "string_gain_pair_2": 0.6, "string_gain_pair_10": 0.4}
    comparison = BaselineComparison(SUMO_PLEXE, ours, plexe, "Plexe")
    assert comparison.compared_metrics() == ["string_gain", "min_gap_m", "string_gain_pair_1", "string_gain_pair_2",
                                             "string_gain_pair_10"]
    assert comparison.as_dict()["metrics"]["string_gain_pair_1"] == {"ours": 0.7, "baseline": 0.8}
    assert comparison.failure_reason() == "ours damps worse than the sumo-plexe baseline: string_gain 0.900 > 0.800"
