import pytest
from drivers import fired
from platoon_drivers import CLOSE_GAP_M, CUT_IN, DRIVERS, JOINING, PARTNER, PLATOONING, platoon_world
from planner_world import DT_S, ego, inputs, planner, rsu_start, scene, transitions

from coopdrive.v1 import planner_pb2

LEAVE_TIME_GAP_S = 2.5


def step(p, t, **world):
    return p.step(t, platoon_world(t, **world))


def joining(p):
    return JOINING.run(p)[1]


def joined(p):
    return PLATOONING.run(p)[1]


def test_the_platoon_waits_for_the_rsu_then_joins_behind_the_partner_and_platoons():
    p = planner()
    _, state = step(p, 0.0, start=False)
    assert state.state == "IDLE" and state.machine == "platooning"
    request, state = step(p, 0.1)
    assert state.state == "JOINING"
    assert request.targets[0].station_id == PARTNER and request.spacing.time_gap_s == 0.5
    _, state = step(p, 0.2, gap_m=CLOSE_GAP_M)
    assert state.state == "PLATOONING"
    assert ("JOINING", "PLATOONING") in transitions(state)


def test_a_member_may_go_a_little_faster_than_its_cruise_speed_to_keep_up_with_its_partner():
    p = planner()
    request, _ = joining(p)
    config = p.config
    assert request.desired_speed_mps == pytest.approx(config.cruise_speed_mps + config.platoon.member_speed_headroom_mps)
    assert request.desired_speed_mps > 60 / 3.6


def test_a_platoon_head_with_no_one_ahead_drives_at_the_platoon_speed():
    p = planner()
    world = inputs(planner_pb2.SCENARIO_PLATOON, platoon_id=2, ego=ego(), iclcms={900: rsu_start(0.1)}, scene=scene())
    p.step(0.0, world)
    request, state = p.step(0.1, world)
    assert state.state == "JOINING"
    assert request.desired_speed_mps == pytest.approx(60 / 3.6)


def test_a_silent_partner_degrades_the_platoon_to_acc_and_its_return_rejoins():
    p = planner()
    joined(p)
    request, state = step(p, 0.8, gap_m=CLOSE_GAP_M, heard_at=0.3)
    assert state.state == "DEGRADED_ACC" and request.spacing.time_gap_s == 1.5
    assert "400 ms" in state.recent_transitions[-1].reason
    _, state = step(p, 0.9, gap_m=CLOSE_GAP_M)
    assert state.state == "PLATOONING"
    assert ("DEGRADED_ACC", "JOINING") in transitions(state)


def test_joining_that_never_closes_the_gap_escapes_to_follow_safe_after_its_timeout():
    p = planner()
    joining(p)
    _, state = step(p, 30.2)
    assert state.state == "FOLLOW_SAFE"
    assert state.recent_transitions[-1].event == "TIMEOUT"


def test_a_partner_silent_while_joining_ends_in_follow_safe_and_rejoins_when_heard():
    p = planner()
    joining(p)
    _, state = step(p, 0.7, heard_at=0.1)
    assert state.state == "FOLLOW_SAFE"
    _, state = step(p, 0.8)
    assert state.state == "JOINING"


def test_a_leave_request_opens_the_gap_and_ends_out_of_the_platoon():
    p = planner()
    joined(p)
    request, state = step(p, 0.3, gap_m=CLOSE_GAP_M, leave=True)
    assert state.state == "LEAVING" and request.spacing.time_gap_s == 2.5
    _, state = step(p, 0.4, gap_m=50.0, leave=True)
    assert state.state == "DONE"


def test_leaving_ends_after_its_timeout_even_if_the_gap_never_opens():
    p = planner()
    joined(p)
    step(p, 0.3, gap_m=CLOSE_GAP_M, end=True)
    _, state = step(p, 15.3 + DT_S, gap_m=CLOSE_GAP_M, end=True)
    assert state.state == "DONE" and state.recent_transitions[-1].event == "TIMEOUT"


@pytest.mark.parametrize("source", ["IDLE", "JOINING", "PLATOONING", "DEGRADED_ACC", "FOLLOW_SAFE"])
def test_the_rsu_end_of_scenario_makes_the_vehicle_leave_from_every_state_before_leaving(source):
    request, state = DRIVERS[("platooning", source, "END_OF_SCENARIO", "LEAVING")]()
    assert state.state == "LEAVING"
    assert fired(state, source, "END_OF_SCENARIO", "LEAVING").reason == "RSU endOfScenario"
    assert request.spacing.time_gap_s == LEAVE_TIME_GAP_S


@pytest.mark.parametrize("source", ["JOINING", "PLATOONING", "DEGRADED_ACC", "FOLLOW_SAFE"])
def test_a_leave_request_opens_the_gap_from_every_platoon_state(source):
    request, state = DRIVERS[("platooning", source, "LEAVE_REQUESTED", "LEAVING")]()
    assert state.state == "LEAVING"
    assert fired(state, source, "LEAVE_REQUESTED", "LEAVING").reason == "leave requested"
    assert request.spacing.time_gap_s == LEAVE_TIME_GAP_S
    assert [t.station_id for t in request.targets] == [PARTNER]


def test_a_vehicle_cutting_in_while_joining_makes_the_joiner_follow_it_with_the_acc_gap():
    request, state = DRIVERS[("platooning", "JOINING", "SCENE_CONTRADICTS_V2V", "FOLLOW_SAFE")]()
    assert state.state == "FOLLOW_SAFE"
    assert fired(state, "JOINING", "SCENE_CONTRADICTS_V2V", "FOLLOW_SAFE").reason == "scene: a vehicle cut in"
    assert request.spacing.time_gap_s == 1.5
    assert [(t.object_id, t.role) for t in request.targets] == [(CUT_IN, planner_pb2.TARGET_ROLE_PREDECESSOR)]


def test_the_operator_can_force_the_platoon_out_of_joining():
    p = planner()
    joining(p)
    p.force("FOLLOW_SAFE", 0.15, who="operator HMI")
    _, state = step(p, 0.15, start=False)
    last = [t for t in state.recent_transitions if t.forced][-1]
    assert last.to_state == "FOLLOW_SAFE" and last.reason == "forced by operator HMI"


def test_a_vehicle_cutting_in_before_the_partner_degrades_the_platoon_until_it_leaves():
    p = planner()
    joined(p)
    world = platoon_world(0.3, gap_m=30.0, cut_in=True)
    request, state = p.step(0.3, world)
    assert state.state == "DEGRADED_ACC" and state.recent_transitions[-1].event == "SCENE_CONTRADICTS_V2V"
    assert request.spacing.time_gap_s == 1.5
    _, state = p.step(0.4, world)
    assert state.state == "DEGRADED_ACC"
    _, state = step(p, 0.5, gap_m=CLOSE_GAP_M)
    assert state.state == "PLATOONING"
