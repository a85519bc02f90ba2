"""What each stack vehicle of a scenario-file run is told about itself."""

import math
from pathlib import Path

import pytest

from coopdrive.launch.run import RunOptions, build_specs


def test_a_stack_may_cruise_as_fast_as_the_leader_it_follows_ever_goes(tmp_path):
    specs = {(s.vehicle_id, s.service): s.config
             for s in build_specs(RunOptions(scenario="string", stacks=2), tmp_path)}
    # The string leader oscillates +-10 km/h around 80 km/h: its followers must not be capped at 80 km/h.
    assert specs[(next(v for v, service in specs if v != "world"), "planner")]["logic"]["cruise_speed_mps"] > 24.9


def test_each_stack_allows_its_own_steering_and_brake_actuators_their_response_time_before_blaming_the_driver(
        tmp_path):
    example = Path(__file__).parents[2] / "services" / "sim" / "examples" / "string_stability.yaml"
    specs = {(s.vehicle_id, s.service): s.config for s in build_specs(RunOptions(scenario=str(example)), tmp_path)}
    car, truck = (specs[(vehicle, "actuation")]["actuator"]["override"] for vehicle in ("ego", "truck"))
    # Steering: 3 time constants plus dead time (car 0.1 s and 0.05 s, truck 0.2 s and 0.1 s).
    assert car["steering_response_s"] == pytest.approx(0.35)
    assert truck["steering_response_s"] == pytest.approx(0.7)
    assert truck["brake_release_grace_s"] > car["brake_release_grace_s"]


def test_each_stack_reads_its_nmea_fixes_from_the_simulated_receiver_and_knows_its_output_latency(tmp_path):
    specs = {(s.vehicle_id, s.service): s.config
             for s in build_specs(RunOptions(scenario="string", stacks=2), tmp_path)}
    geolocation = specs[(next(v for v, service in specs if v != "world"), "geolocation")]
    assert geolocation["gnss_port"].endswith("-gnss0")
    # The simulated receiver's 20 ms and, in the real world, its 5 ms jitter's mean: without them every
    # estimate trailed its car by 0.5 m at 90 km/h.
    assert geolocation["gnss_receiver_latency_s"] == pytest.approx(0.02 + math.sqrt(2.0 / math.pi) * 0.005)
    assert geolocation["geolocator"]["gnss_time_jitter_s"] == pytest.approx(0.005)
    # Its correlated error and its stamps' error are the geolocator's defaults (a receiver's figures).
    assert "gnss_error_std_m" not in geolocation["geolocator"]
    assert "gnss_time_error_std_s" not in geolocation["geolocator"]


def test_in_the_ideal_world_the_simulator_runs_it_and_the_stacks_are_told_fixed_latencies(tmp_path):
    specs = {(s.vehicle_id, s.service): s.config
             for s in build_specs(RunOptions(scenario="string", stacks=2, world="ideal"), tmp_path)}
    assert specs[("world", "sim")]["world_profile"] == "ideal"
    geolocation = specs[(next(v for v, service in specs if v != "world"), "geolocation")]
    assert geolocation["gnss_receiver_latency_s"] == pytest.approx(0.02)
    assert geolocation["geolocator"]["gnss_time_jitter_s"] == 0.0
    # A white receiver with a fixed latency: no correlated error to model, and exact stamps.
    assert geolocation["geolocator"]["gnss_error_std_m"] == 0.0
    assert geolocation["geolocator"]["gnss_time_error_std_s"] == 0.0
