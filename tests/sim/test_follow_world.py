"""FollowWorld: the built-in follow world, and the lockstep steps it takes off the actuators' dead times."""

import pytest

from coopdrive.services.sim.world_config import VehicleSpec, WorldConfig
from coopdrive.services.sim.world_service import FollowWorld

STEP_S = 0.02
LEADER_PROFILE = [(0.0, 15.0), (1.0, 15.0), (2.0, 20.0), (4.0, 20.0)]


def world(already_delayed_steps: int, ego_dead_time_s: float = 0.1) -> FollowWorld:
    config = WorldConfig(vehicles=[
        VehicleSpec(vehicle_id="leader", station_m=40.0, speed_profile=LEADER_PROFILE),
        VehicleSpec(vehicle_id="ego", dead_time_s=ego_dead_time_s)])
    return FollowWorld(config, STEP_S, already_delayed_steps=already_delayed_steps)


def drive(follow_world: FollowWorld, requests_late_by_steps: int, steps: int = 200) -> dict[str, list[float]]:
    """Steps the world with an accel pulse for the ego that reaches the model this many steps late."""
    speeds: dict[str, list[float]] = {"leader": [], "ego": []}
    for step in range(steps):
        sent_at_step = step - requests_late_by_steps
        request_mps2 = 1.5 if 10 <= sent_at_step < 60 else 0.0
        follow_world.step(step * STEP_S, STEP_S, {"ego": request_mps2}, {"ego": 0.0})
        for vehicle_id, history in speeds.items():
            history.append(follow_world.bodies[vehicle_id].speed_mps)
    return speeds


def test_the_steps_a_command_spends_in_the_pipeline_are_taken_off_the_ego_dead_time():
    direct = drive(world(already_delayed_steps=0), requests_late_by_steps=0)
    pipelined = drive(world(already_delayed_steps=2), requests_late_by_steps=2)
    assert pipelined["ego"] == pytest.approx(direct["ego"])
    assert max(direct["ego"]) > 16.0, "the pulse never moved the ego"


def test_a_scripted_leader_drives_its_profile_the_same_however_many_steps_are_in_flight():
    assert drive(world(already_delayed_steps=2), 2)["leader"] == drive(world(already_delayed_steps=0), 0)["leader"]


def test_no_more_steps_are_pipelined_than_the_shortest_stack_dead_time_holds():
    # 0.06 s is three steps, one of which stays in the model.
    assert world(already_delayed_steps=5, ego_dead_time_s=0.06).pipelined_steps == 2
    assert world(already_delayed_steps=1, ego_dead_time_s=0.06).pipelined_steps == 1
    assert world(already_delayed_steps=3, ego_dead_time_s=0.0).pipelined_steps == 0
