import pytest
from drivers import fired
from merge_drivers import (A_PARTNER, ACKED, B_AHEAD, B_MIO, B_PARTNER, DRIVERS, GAP_MAKER_STATES, LANE_A, LANE_B,
                           PAIRING, PARTNER_STATES, gap_maker, merger)
from planner_world import ME, ROADWORKS, denm, ego, iclcm, inputs, obj, planner, rsu_start, scene

from coopdrive.v1 import header_pb2, planner_pb2


def gap_maker_pairing(p):
    return PAIRING.run(p)[1]


def own_lane(source: str) -> int:
    return LANE_B if source in (*GAP_MAKER_STATES, "IDLE", "PLATOONING", "SAFE_KEEP_LANE") else LANE_A


def assert_keeps_its_lane_without_protocol_flags(request, lane):
    assert request.target_lane_index == lane and request.lane_change_duration_s == 0.0
    assert request.spacing.time_gap_s == 1.5 and request.desired_speed_mps == pytest.approx(40 / 3.6)
    assert not any(t.role == planner_pb2.TARGET_ROLE_VIRTUAL for t in request.targets)
    i = request.iclcm
    assert not (i.safe_to_merge or i.merge_request or i.merge_flag or i.merge_flag_head)


def test_a_lane_b_vehicle_pairs_makes_a_gap_sends_stom_and_platoons_behind_its_merged_partner():
    p = planner()
    _, state = p.step(0.0, gap_maker(0.0, start=False, roadworks=False))
    assert state.state == "IDLE"
    request, state = p.step(0.1, gap_maker(0.1, roadworks=False))
    assert state.state == "PLATOONING" and request.desired_speed_mps == pytest.approx(60 / 3.6)
    request, state = p.step(0.2, gap_maker(0.2))
    assert state.state == "PAIRING" and request.iclcm.forward_id == A_PARTNER
    request, state = p.step(0.3, gap_maker(0.3, ACKED))
    assert state.state == "GAP_MAKING"
    virtual = [t for t in request.targets if t.role == planner_pb2.TARGET_ROLE_VIRTUAL]
    assert virtual[0].station_id == A_PARTNER and virtual[0].extra_gap_m == 6.0
    assert request.desired_speed_mps == pytest.approx(40 / 3.6)
    assert any(t.role == planner_pb2.TARGET_ROLE_PREDECESSOR and t.station_id == B_MIO for t in request.targets)
    request, state = p.step(0.4, gap_maker(0.4, ACKED, partner_gap_m=25.0))
    assert state.state == "WAIT_MERGE" and request.iclcm.safe_to_merge
    _, state = p.step(0.5, gap_maker(0.5, ACKED, partner_gap_m=25.0, partner_lane=LANE_B))
    assert state.state == "DONE"


def test_a_lane_b_vehicle_with_nobody_ahead_in_lane_a_has_no_gap_to_make():
    p = planner()
    p.step(0.0, gap_maker(0.0, partner=False))
    _, state = p.step(0.1, gap_maker(0.1, partner=False))
    assert state.state == "DONE"


@pytest.mark.parametrize("reach, timeout_s", [
    (lambda p: p.step(0.2, gap_maker(0.2)), 5.0),
    (lambda p: p.step(0.3, gap_maker(0.3, ACKED)), 20.0),
    (lambda p: p.step(0.4, gap_maker(0.4, ACKED, partner_gap_m=25.0)), 15.0),
], ids=["missing acknowledge", "gap never opens", "partner never merges"])
def test_each_gap_maker_wait_escapes_to_keep_lane_after_its_timeout(reach, timeout_s):
    p = planner()
    gap_maker_pairing(p)
    _, state = reach(p)
    waiting, since = state.state, state.recent_transitions[-1].time_s
    t = round(since + timeout_s, 3)
    msg = ACKED if waiting != "PAIRING" else None
    gap = 25.0 if waiting == "WAIT_MERGE" else 5.0
    _, state = p.step(t, gap_maker(t, msg, partner_gap_m=gap))
    assert state.state == "SAFE_KEEP_LANE"
    last = state.recent_transitions[-1]
    assert (last.from_state, last.event) == (waiting, "TIMEOUT")


def test_keep_lane_retries_the_pairing_while_the_road_works_last():
    p = planner()
    gap_maker_pairing(p)
    p.step(5.2, gap_maker(5.2))
    _, state = p.step(10.3, gap_maker(10.3))
    assert state.state == "PAIRING" and state.recent_transitions[-1].event == "RETRY"


@pytest.mark.parametrize("source", PARTNER_STATES)
def test_a_partner_silent_for_400_ms_ends_each_partner_state_at_once_and_the_vehicle_keeps_its_lane(source):
    request, state = DRIVERS[("merge", source, "PARTNER_LOST", "SAFE_KEEP_LANE")]()
    assert state.state == "SAFE_KEEP_LANE"
    assert fired(state, source, "PARTNER_LOST", "SAFE_KEEP_LANE").reason == "partner silent for 400 ms"
    assert_keeps_its_lane_without_protocol_flags(request, own_lane(source))
    assert request.iclcm.forward_id == 0 and request.iclcm.backward_id == 0


@pytest.mark.parametrize("source", PARTNER_STATES)
def test_a_scene_that_puts_the_partner_on_the_wrong_side_ends_each_partner_state_and_the_vehicle_keeps_its_lane(
        source):
    request, state = DRIVERS[("merge", source, "SCENE_CONTRADICTS_V2V", "SAFE_KEEP_LANE")]()
    assert state.state == "SAFE_KEEP_LANE"
    assert fired(state, source, "SCENE_CONTRADICTS_V2V", "SAFE_KEEP_LANE").reason \
        == "scene contradicts the partner's V2V"
    assert_keeps_its_lane_without_protocol_flags(request, own_lane(source))
    assert request.iclcm.forward_id == 0 and request.iclcm.backward_id == 0


def test_road_works_heard_before_the_rsu_start_begin_the_pairing_from_idle():
    request, state = DRIVERS[("merge", "IDLE", "ROADWORKS", "PAIRING")]()
    assert state.state == "PAIRING" and fired(state, "IDLE", "ROADWORKS", "PAIRING").reason == "road works DENM"
    assert request.iclcm.forward_id == A_PARTNER and request.target_lane_index == LANE_B


def test_a_gap_maker_whose_partner_acknowledges_another_vehicle_lets_it_go_and_has_no_gap_to_make():
    request, state = DRIVERS[("merge", "PAIRING", "NO_PARTNER", "DONE")]()
    assert state.state == "DONE" and fired(state, "PAIRING", "NO_PARTNER", "DONE")
    assert request.iclcm.forward_id == 0
    assert_keeps_its_lane_without_protocol_flags(request, LANE_B)


def test_a_lane_a_vehicle_pairs_waits_for_the_head_flag_and_merges_on_stom():
    p = planner()
    p.step(0.0, merger(0.0))
    request, state = p.step(0.1, merger(0.1))
    assert state.state == "PAIRING" and request.iclcm.backward_id == B_PARTNER
    request, state = p.step(0.2, merger(0.2, {"forward_id": ME}))
    assert state.state == "WAIT_HEAD" and request.iclcm.acknowledge and not request.iclcm.merge_flag_head
    request, state = p.step(0.3, merger(0.3, {"forward_id": ME}, head=True))
    assert state.state == "WAIT_STOM" and request.iclcm.merge_flag_head and request.iclcm.merge_request
    assert request.iclcm.merge_flag_tail
    assert any(t.role == planner_pb2.TARGET_ROLE_VIRTUAL and t.station_id == B_AHEAD for t in request.targets)
    request, state = p.step(0.4, merger(0.4, {"forward_id": ME, "merge_safe_to_merge": True}, head=True))
    assert state.state == "MERGING" and request.target_lane_index == LANE_B
    assert request.lane_change_duration_s == 6.0 and request.iclcm.merge_flag
    request, state = p.step(5.0, merger(5.0, {"forward_id": ME}, head=True, ego_lane=LANE_B))
    assert state.state == "DONE" and not request.iclcm.merge_flag_head


def test_a_lane_a_vehicle_with_nobody_behind_in_lane_b_merges_on_the_scenes_gap():
    p = planner()
    p.step(0.0, merger(0.0, partner=False))
    _, state = p.step(0.1, merger(0.1, partner=False, head=True))
    assert state.state == "MERGING"


@pytest.mark.parametrize("head, timeout_s, waiting", [(False, 60.0, "WAIT_HEAD"), (True, 10.0, "WAIT_STOM")],
                         ids=["head flag never ours", "missing STOM"])
def test_each_merger_wait_escapes_to_keep_lane_after_its_timeout(head, timeout_s, waiting):
    p = planner()
    p.step(0.0, merger(0.0))
    p.step(0.1, merger(0.1, {"forward_id": ME}, head=head))
    _, state = p.step(0.2, merger(0.2, {"forward_id": ME}, head=head))
    assert state.state == waiting
    since = state.recent_transitions[-1].time_s
    request, state = p.step(since + timeout_s, merger(since + timeout_s, {"forward_id": ME}, head=head))
    assert state.state == "SAFE_KEEP_LANE" and request.target_lane_index == LANE_A


def test_a_lane_change_not_done_in_time_escapes_to_keep_lane():
    p = planner()
    p.step(0.0, merger(0.0, partner=False))
    p.step(0.1, merger(0.1, partner=False, head=True))
    _, state = p.step(12.1, merger(12.1, partner=False, head=True))
    assert state.state == "SAFE_KEEP_LANE" and state.recent_transitions[-1].from_state == "MERGING"


@pytest.mark.parametrize("source", ["IDLE", "PLATOONING", "SAFE_KEEP_LANE", *PARTNER_STATES])
def test_the_rsu_end_of_scenario_ends_the_merge_from_every_state_but_a_lane_change_and_the_vehicle_keeps_its_lane(
        source):
    request, state = DRIVERS[("merge", source, "END_OF_SCENARIO", "DONE")]()
    assert state.state == "DONE"
    assert fired(state, source, "END_OF_SCENARIO", "DONE").reason == "RSU endOfScenario"
    assert_keeps_its_lane_without_protocol_flags(request, own_lane(source))


def merger_among_traffic(t, behind_gap_m, behind_speed_mps, ego_lane=LANE_A, works_east_m=None):
    """Head of lane A; in lane B only a car that sends CAMs but never an iCLCM (it ignores the protocol)."""
    world = scene(obj(3, B_PARTNER, behind_gap_m, LANE_B, speed_mps=behind_speed_mps), ego_lane=ego_lane,
                  neighbours={-1: (None, 3)})
    return inputs(planner_pb2.SCENARIO_MERGE, platoon_id=1, ego=ego(ego_lane, speed_mps=11.0), scene=world,
                  iclcms={900: rsu_start(t)}, denms={900: denm(ROADWORKS, metres_east=works_east_m)})


def run_merger(p, steps, **kwargs):
    for i in range(steps):
        request, state = p.step(i * 0.1, merger_among_traffic(i * 0.1, **kwargs))
    return request, state


def test_a_lane_a_vehicle_does_not_pair_with_a_car_that_never_sent_an_iclcm_and_merges_on_the_scenes_gap():
    request, state = run_merger(planner(), 5, behind_gap_m=-40.0, behind_speed_mps=11.0)
    assert state.state == "MERGING" and request.iclcm.backward_id == 0
    assert [t.to_state for t in state.recent_transitions][-3:] == ["WAIT_HEAD", "WAIT_STOM", "MERGING"]


def test_a_fast_car_closing_in_from_behind_in_lane_b_keeps_the_merger_waiting():
    _, state = run_merger(planner(), 20, behind_gap_m=-30.0, behind_speed_mps=17.0)
    assert state.state == "WAIT_STOM"


def test_a_vehicle_still_in_the_closed_lane_stops_before_the_road_works():
    request, _ = run_merger(planner(), 3, behind_gap_m=-5.0, behind_speed_mps=17.0, works_east_m=200.0)
    assert request.has_stop_line
    assert request.stop_line_distance_m == pytest.approx(190.0, abs=1.0)


def test_a_vehicle_in_the_open_lane_has_no_stop_line_for_the_works():
    request, _ = run_merger(planner(), 3, behind_gap_m=-40.0, behind_speed_mps=11.0, works_east_m=200.0,
                            ego_lane=LANE_B)
    assert not request.has_stop_line


def test_a_merger_answers_the_lane_b_vehicle_that_names_it_rather_than_the_one_the_scene_puts_behind():
    namer = 61
    p = planner()
    p.step(0.0, merger(0.0))
    request, state = p.step(0.1, merger(0.1))
    assert state.state == "PAIRING" and request.iclcm.backward_id == B_PARTNER
    named = merger(0.2)
    named.iclcms[namer] = iclcm(namer, 0.2, forward_id=ME)
    request, state = p.step(0.2, named)
    assert request.iclcm.backward_id == namer and request.iclcm.acknowledge


def test_a_merger_whose_partner_names_another_merger_lets_it_go_and_merges_on_the_scenes_gap():
    p = planner()
    p.step(0.0, merger(0.0))
    request, state = p.step(0.1, merger(0.1))
    assert state.state == "PAIRING" and request.iclcm.backward_id == B_PARTNER
    elsewhere = {"forward_id": 4242}
    _, state = p.step(0.2, merger(0.2, elsewhere))
    request, state = p.step(0.3, merger(0.3, elsewhere))
    assert state.state == "WAIT_HEAD" and request.iclcm.backward_id == 0


B_ALONGSIDE = 61


def head_of_lane_a_given_stom(t, beside, neighbours):
    """Head of lane A, paired and given STOM by its partner 30 m back, with `beside` in its scene too."""
    msgs = {900: rsu_start(t), B_PARTNER: iclcm(B_PARTNER, t, forward_id=ME, merge_safe_to_merge=True)}
    world = scene(beside, obj(3, B_PARTNER, -30.0, LANE_B, speed_mps=11.5), ego_lane=LANE_A, neighbours=neighbours)
    return inputs(planner_pb2.SCENARIO_MERGE, platoon_id=1, ego=ego(LANE_A, speed_mps=11.5), scene=world,
                  iclcms=msgs, denms={900: denm(ROADWORKS)})


def merger_beside_a_lane_b_car(t, alongside_gap_m):
    """Another lane B car (b1 of merge seed 3) drives beside us: its rear bumper alongside_gap_m from our front
    bumper."""
    alongside = obj(6, B_ALONGSIDE, alongside_gap_m, LANE_B, speed_mps=11.5)
    alongside.length_m.value, alongside.length_m.confidence = 4.5, 0.7
    return head_of_lane_a_given_stom(t, alongside, {-1: (6, 3) if alongside_gap_m >= 0 else (None, 6)})


def test_a_merger_given_stom_waits_while_a_lane_b_car_drives_beside_it_and_drops_back_behind_it():
    p = planner()
    for i in range(4):
        request, state = p.step(i * 0.1, merger_beside_a_lane_b_car(i * 0.1, alongside_gap_m=-2.5))
    assert state.state == "WAIT_STOM"
    assert request.desired_speed_mps == pytest.approx(11.5 - 2.0)
    # Its front half a metre behind our rear bumper: still too close to turn in ahead of it.
    request, state = p.step(0.4, merger_beside_a_lane_b_car(0.4, alongside_gap_m=-9.5))
    assert state.state == "WAIT_STOM"
    # Ahead of us but by less than the standstill distance (6 m): not yet.
    request, state = p.step(0.5, merger_beside_a_lane_b_car(0.5, alongside_gap_m=3.0))
    assert state.state == "WAIT_STOM"
    # Far enough ahead: STOM from the partner behind holds again.
    request, state = p.step(0.6, merger_beside_a_lane_b_car(0.6, alongside_gap_m=7.0))
    assert state.state == "MERGING"


def merger_with_only_a_sonar_echo_beside_it(t, echo_lateral_m):
    """The lane B car beside us is missing from the scene's neighbours (its track being handed over, merge
    seed 4): only a side sonar feels it, echo_lateral_m to our side."""
    echo = obj(56, gap_m=1.6, lane=LANE_B, y_m=echo_lateral_m)
    echo.lateral_offset_m = echo_lateral_m
    echo.lane_index.confidence = -1.0
    echo.position.sources.append(header_pb2.SENSOR_SOURCE_SONAR)
    return head_of_lane_a_given_stom(t, echo, {-1: (None, 3)})


def test_a_merger_given_stom_does_not_turn_into_a_car_only_its_side_sonar_feels():
    p = planner()
    for i in range(4):
        _, state = p.step(i * 0.1, merger_with_only_a_sonar_echo_beside_it(i * 0.1, echo_lateral_m=-2.0))
    assert state.state == "WAIT_STOM"
    # An echo on the other side (a lane A car, or the guardrail) is no reason to wait.
    _, state = p.step(0.4, merger_with_only_a_sonar_echo_beside_it(0.4, echo_lateral_m=2.0))
    assert state.state == "MERGING"
