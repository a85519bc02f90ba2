"""ScenarioSim: the world of a scenario file, stepped without any bus."""

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_config import parse_scenario
from coopdrive.services.sim.scenario_sim import ScenarioSim, StackCommand

STEP_S = 0.02


def scenario(**extra):
    data = {
        "name": "t", "map": "a270", "duration_s": 10, "seed": 3,
        "vehicles": [
            {"vehicle_id": "lead", "station_id": 1, "role": "scripted", "lane": 0, "station_m": 300, "speed_mps": 20},
            {"vehicle_id": "a", "station_id": 2, "lane": 0, "station_m": 250, "speed_mps": 20},
            {"vehicle_id": "b", "station_id": 3, "lane": 0, "station_m": 200, "speed_mps": 20},
        ],
        "judging": {"platoon": ["lead", "a", "b"]},
    }
    data.update(extra)
    return parse_scenario(data)


@pytest.fixture(scope="module")
def a270():
    return RoadMap.load("a270")


def run(sim, seconds, command=None):
    for k in range(1, int(round(seconds / STEP_S)) + 1):
        if command is not None:
            sim.apply_command("a", command)
        sim.step(k * STEP_S)
    return {t.vehicle_id: t for t in sim.truths()}


def test_a_stack_vehicle_under_full_brake_stops_and_one_without_commands_holds_its_speed(a270):
    sim = ScenarioSim(scenario(), a270, ["a", "b"])
    truths = run(sim, 6.0, StackCommand(accel_request_mps2=-8.0))
    assert truths["a"].speed_mps < 0.5
    assert truths["b"].speed_mps == pytest.approx(20.0, abs=0.3)


def test_the_safety_driver_keeps_an_unsteered_vehicle_in_its_lane_through_the_bends(a270):
    sim = ScenarioSim(scenario(), a270, ["a", "b"])
    truths = run(sim, 10.0)
    assert truths["b"].lane_index == 0 and abs(truths["b"].lateral_offset_m) < 0.3


def test_stack_vehicles_without_a_stack_in_this_run_are_left_out(a270):
    sim = ScenarioSim(scenario(), a270, ["a"])
    ids = [t.vehicle_id for t in sim.truths()]
    assert ids == ["lead", "a"]
    assert sim.config.judging.platoon == ["lead", "a"]
    assert set(sim.sensor_outputs(0.1)) == {"a"}


def test_a_vehicle_id_that_is_not_a_stack_vehicle_is_refused_by_name(a270):
    with pytest.raises(ValueError, match="lead"):
        ScenarioSim(scenario(), a270, ["lead"])


def test_the_world_is_the_same_for_the_same_seed(a270):
    def sensor_bytes():
        sim = ScenarioSim(scenario(), a270, ["a", "b"])
        run(sim, 1.0, StackCommand(accel_request_mps2=0.5))
        outputs = sim.sensor_outputs(1.0)
        return [m.SerializeToString() for m in outputs["a"].can_state + outputs["a"].radar]

    assert sensor_bytes() == sensor_bytes()


def test_the_lockstep_delay_is_taken_off_the_actuator_dead_time(a270):
    plain = ScenarioSim(scenario(), a270, ["a"])
    delayed = ScenarioSim(scenario(), a270, ["a"], already_delayed_steps=1)
    assert delayed.objects.models["a"].profile.response_dead_time_s == pytest.approx(
        plain.objects.models["a"].profile.response_dead_time_s - STEP_S)


def test_no_more_lockstep_steps_are_taken_off_than_the_shortest_dead_time_holds(a270):
    # The passenger car's steering dead time, 0.05 s, holds two whole 0.02 s steps.
    sim = ScenarioSim(scenario(), a270, ["a"], already_delayed_steps=5)
    assert sim.pipelined_steps == 2
    assert sim.objects.models["a"].profile.steer_dead_time_s == pytest.approx(0.05 - 2 * STEP_S)
