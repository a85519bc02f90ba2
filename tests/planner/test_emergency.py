import pytest
from planner_world import EMERGENCY_APPROACHING, denm, ego, emergency_cam, inputs, planner, scene

from coopdrive.v1 import planner_pb2

EV = 66


def world(t, ev_east_m=None, offset_m=0.0, lane=1, with_denm=False, heard_at=None,
          scenario=planner_pb2.SCENARIO_EMERGENCY):
    cams = {} if ev_east_m is None else {EV: emergency_cam(EV, t if heard_at is None else heard_at, ev_east_m)}
    denms = {EV: denm(EMERGENCY_APPROACHING, origin=EV)} if with_denm else {}
    return inputs(scenario, ego=ego(lane, lateral_offset_m=offset_m), scene=scene(ego_lane=lane), cams=cams,
                  denms=denms)


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
