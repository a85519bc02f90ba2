import pytest
from drivers import fired
from emergency_drivers import DRIVERS, world
from planner_world import planner

from coopdrive.v1 import planner_pb2


def opened(p):
    p.step(0.0, world(0.0))
    p.step(0.1, world(0.1, -100.0))
    return p.step(0.2, world(0.2, -80.0, offset_m=0.9))


def test_a_left_lane_vehicle_opens_the_corridor_to_its_left_edge_and_closes_it_after_the_ev_passed():
    p = planner()
    request, state = p.step(0.0, world(0.0))
    assert state.state == "NORMAL" and request.lateral_offset_m == 0.0
    request, state = p.step(0.1, world(0.1, -100.0))
    assert state.state == "OPENING"
    assert request.lateral_offset_m == pytest.approx(0.9)
    assert request.desired_speed_mps == pytest.approx(30 / 3.6)
    _, state = p.step(0.2, world(0.2, -80.0, offset_m=0.9))
    assert state.state == "HOLD_CORRIDOR"
    request, state = p.step(3.0, world(3.0, 20.0, offset_m=0.9))
    assert state.state == "CLOSING" and request.lateral_offset_m == 0.0
    _, state = p.step(4.0, world(4.0, 60.0, offset_m=0.1))
    assert state.state == "NORMAL"


def test_a_right_lane_vehicle_opens_the_corridor_to_its_right_edge():
    p = planner()
    p.step(0.0, world(0.0, lane=0))
    request, _ = p.step(0.1, world(0.1, -100.0, lane=0))
    assert request.lateral_offset_m == pytest.approx(-0.9)


def test_a_denm_alone_opens_the_corridor_and_a_hold_that_never_ends_escapes_to_slow_safe():
    p = planner()
    p.step(0.0, world(0.0))
    _, state = p.step(0.1, world(0.1, with_denm=True))
    assert state.state == "OPENING"
    p.step(0.2, world(0.2, offset_m=0.9, with_denm=True))
    request, state = p.step(60.2, world(60.2, offset_m=0.9, with_denm=True))
    assert state.state == "SLOW_SAFE" and state.recent_transitions[-1].event == "TIMEOUT"
    assert request.lateral_offset_m == 0.0


def test_a_corridor_that_cannot_be_opened_in_time_escapes_to_slow_safe():
    p = planner()
    p.step(0.0, world(0.0))
    p.step(0.1, world(0.1, -100.0))
    _, state = p.step(8.1, world(8.1, -60.0))
    assert state.state == "SLOW_SAFE"


def test_an_ev_no_longer_heard_closes_the_corridor():
    p = planner()
    opened(p)
    _, state = p.step(3.3, world(3.3, -80.0, offset_m=0.9, heard_at=0.2))
    assert state.state == "CLOSING" and "no longer heard" in state.recent_transitions[-1].reason


def test_a_corridor_that_cannot_be_closed_in_time_escapes_to_slow_safe():
    p = planner()
    opened(p)
    p.step(3.0, world(3.0, 20.0, offset_m=0.9))
    _, state = p.step(11.0, world(11.0, 100.0, offset_m=0.9))
    assert state.state == "SLOW_SAFE"


def test_a_handled_denm_does_not_reopen_the_corridor():
    p = planner()
    p.step(0.0, world(0.0))
    p.step(0.1, world(0.1, -100.0, with_denm=True))
    p.step(0.2, world(0.2, -80.0, offset_m=0.9, with_denm=True))
    p.step(3.0, world(3.0, 20.0, offset_m=0.9, with_denm=True))
    p.step(4.0, world(4.0, 60.0, with_denm=True))
    _, state = p.step(4.1, world(4.1, 70.0, with_denm=True))
    assert state.state == "NORMAL"


def test_plain_following_is_the_emergency_machines_normal_driving():
    p = planner()
    request, state = p.step(0.0, world(0.0, scenario=planner_pb2.SCENARIO_FOLLOW))
    assert state.scenario == planner_pb2.SCENARIO_FOLLOW and state.machine == "emergency"
    assert state.state == "NORMAL" and request.desired_speed_mps == 25.0


def test_a_stale_cam_of_a_lost_ev_does_not_reopen_the_corridor():
    p = planner()
    opened(p)
    p.step(3.3, world(3.3, -80.0, offset_m=0.9, heard_at=0.2))
    p.step(4.0, world(4.0, -80.0, offset_m=0.0, heard_at=0.2))
    _, state = p.step(4.1, world(4.1, -80.0, offset_m=0.0, heard_at=0.2))
    assert state.state == "NORMAL"


def test_an_ev_that_passes_before_the_corridor_is_open_brings_the_vehicle_back_to_the_lane_centre_at_once():
    request, state = DRIVERS[("emergency", "OPENING", "EV_PASSED", "CLOSING")]()
    assert state.state == "CLOSING"
    assert fired(state, "OPENING", "EV_PASSED", "CLOSING").reason == "emergency vehicle passed"
    assert request.lateral_offset_m == 0.0


@pytest.mark.parametrize("event, reason", [("EV_PASSED", "emergency vehicle passed"),
                                           ("EV_LOST", "emergency vehicle no longer heard")])
def test_slow_safe_returns_to_normal_driving_once_the_ev_passed_or_is_no_longer_heard(event, reason):
    request, state = DRIVERS[("emergency", "SLOW_SAFE", event, "NORMAL")]()
    assert state.state == "NORMAL" and fired(state, "SLOW_SAFE", event, "NORMAL").reason == reason
    assert request.lateral_offset_m == 0.0 and request.desired_speed_mps == 25.0
