"""The longitudinal controller: law selection, V2V fallback, min-select, limits, emergency, bad input."""

import math

import pytest

from coopdrive.services.control.longitudinal import (
    AccLaw,
    CaccLaw,
    LongitudinalController,
    Spacing,
    SpeedLaw,
    Target,
)
from coopdrive.services.control.profiles import CAR
from coopdrive.v1 import control_pb2, planner_pb2
from coopdrive.vehicle import SPACING as SPACING_POLICY

DT = 0.02
M = control_pb2
SPACING = Spacing(standstill_m=6.0, time_gap_s=0.5)


def steady_target(object_id=1, gap_m=16.0, v2v_age_s=0.04, accel_mps2=0.0, speed_mps=20.0, **kw):
    return Target(object_id=object_id, gap_m=gap_m, speed_mps=speed_mps, accel_mps2=accel_mps2, v2v_age_s=v2v_age_s, **kw)


def run(ctrl, steps, targets, speed_mps=20.0, desired_mps=30.0, spacing=SPACING, start_s=0.0):
    cmd = None
    for k in range(steps):
        cmd = ctrl.step(start_s + k * DT, speed_mps, 0.0, targets, desired_mps, spacing)
    return cmd


def test_without_targets_the_controller_cruises_and_names_no_target():
    cmd = LongitudinalController(CAR).step(0.0, 20.0, 0.0, [], 25.0)
    assert cmd.mode == M.LONGITUDINAL_MODE_CRUISE
    assert cmd.target_object_id == 0
    assert cmd.cruise_speed_mps == 25.0


def test_fresh_v2v_runs_cacc_at_the_planner_time_gap():
    cmd = run(LongitudinalController(CAR), 5, [steady_target()])
    assert cmd.mode == M.LONGITUDINAL_MODE_CACC
    assert cmd.time_gap_s == pytest.approx(0.5)
    assert cmd.desired_gap_m == pytest.approx(6.0 + 0.5 * 20.0)
    assert cmd.gap_m == pytest.approx(16.0)


def test_v2v_older_than_400_ms_falls_back_to_acc_until_the_range_rate_history_allows_dcacc():
    ctrl = LongitudinalController(CAR)
    stale = steady_target(v2v_age_s=0.41)
    assert ctrl.step(0.0, 20.0, 0.0, [stale], 30.0, SPACING).mode == M.LONGITUDINAL_MODE_ACC
    cmd = run(ctrl, 10, [stale], start_s=DT)
    assert cmd.mode == M.LONGITUDINAL_MODE_DCACC


def test_a_target_without_any_v2v_is_followed_on_radar_at_the_raised_acc_time_gap():
    radar_only = steady_target(gap_m=60.0, v2v_age_s=None, accel_mps2=None)
    cmd = LongitudinalController(CAR).step(0.0, 20.0, 0.0, [radar_only], 30.0, SPACING)
    assert cmd.mode == M.LONGITUDINAL_MODE_ACC
    assert cmd.time_gap_s == pytest.approx(CAR.spacing.acc_time_gap_s)


def test_a_new_target_closer_than_the_time_gap_goal_starts_at_its_present_time_gap_and_opens_gently():
    # 12 m at 20 m/s behind a radar-only cut-in: (12 - 6) / 20 = 0.3 s now, 1.5 s wanted.
    ctrl = LongitudinalController(CAR)
    cut_in = steady_target(gap_m=12.0, v2v_age_s=None, accel_mps2=None)
    first = ctrl.step(0.0, 20.0, 0.0, [cut_in], 30.0, SPACING)
    assert first.time_gap_s == pytest.approx(0.3)
    assert first.desired_gap_m == pytest.approx(12.0)
    later = run(ctrl, 50, [cut_in], start_s=DT)
    assert later.time_gap_s == pytest.approx(0.3 + CAR.spacing.time_gap_rate_sps * 50 * DT)


@pytest.mark.parametrize("law", list(CaccLaw))
def test_a_new_target_inside_the_standstill_distance_starts_at_the_smallest_time_gap_and_brakes(law):
    ctrl = LongitudinalController(CAR, cacc_law=law)
    cmd = ctrl.step(0.0, 5.0, 0.0, [steady_target(gap_m=4.0, speed_mps=5.0)], 30.0, SPACING)
    assert cmd.time_gap_s == pytest.approx(0.2)
    assert cmd.accel_request_mps2 < 0


def test_the_fallback_time_gap_ramps_up_instead_of_stepping():
    ctrl = LongitudinalController(CAR)
    run(ctrl, 50, [steady_target()])
    cmd = run(ctrl, 50, [steady_target(v2v_age_s=1.0)], start_s=50 * DT)
    # 1 s after the loss: 0.5 + 0.2 s/s * 1 s, below the dCACC floor of 1.0 s
    assert cmd.time_gap_s == pytest.approx(0.5 + CAR.spacing.time_gap_rate_sps * 50 * DT)
    cmd = run(ctrl, 200, [steady_target(v2v_age_s=1.0)], start_s=100 * DT)
    assert cmd.time_gap_s == pytest.approx(CAR.spacing.dcacc_time_gap_s)


def test_the_closest_target_sets_the_command_because_the_minimum_wins():
    far, near = steady_target(object_id=3, gap_m=40.0), steady_target(object_id=9, gap_m=14.0, speed_mps=19.0)
    cmd = run(LongitudinalController(CAR), 3, [far, near])
    assert cmd.target_object_id == 9
    assert min(cmd.law_outputs_mps2.values()) == cmd.law_outputs_mps2["LONGITUDINAL_MODE_CACC:9"]


def test_a_follow_law_wanting_more_than_the_comfort_limit_keeps_the_vehicle_instead_of_cruise():
    # Predecessor pulling away at 3 m/s2, 8 m beyond the CACC gap, set speed 2.5 m/s above ours: the governor
    # offers 2.5 m/s2 plus drag, the CACC far more; both apply as +2, so the follow law stays in command.
    pulling_away = steady_target(gap_m=24.0, speed_mps=22.0, accel_mps2=3.0)
    cmd = run(LongitudinalController(CAR), 100, [pulling_away], speed_mps=20.0, desired_mps=22.5)
    assert cmd.mode == M.LONGITUDINAL_MODE_CACC and cmd.target_object_id == 1
    assert cmd.accel_request_mps2 == pytest.approx(CAR.limits.max_accel_mps2)


def test_near_the_set_speed_the_governor_caps_a_follow_law_that_wants_to_go_faster():
    pulling_away = steady_target(gap_m=24.0, speed_mps=22.0, accel_mps2=3.0)
    cmd = run(LongitudinalController(CAR), 100, [pulling_away], speed_mps=20.0, desired_mps=20.5)
    assert cmd.mode == M.LONGITUDINAL_MODE_CRUISE
    assert cmd.accel_request_mps2 < 1.0


def test_a_yield_target_keeps_its_extra_gap_on_top_of_the_spacing_policy():
    target = steady_target(gap_m=60.0, role=planner_pb2.TARGET_ROLE_YIELD, extra_gap_m=4.0)
    cmd = run(LongitudinalController(CAR), 2, [target])
    assert cmd.desired_gap_m == pytest.approx(6.0 + 4.0 + 0.5 * 20.0)


def test_normal_commands_respect_the_comfort_and_jerk_limits():
    ctrl = LongitudinalController(CAR)
    last = 0.0
    for k in range(200):
        cmd = ctrl.step(k * DT, 5.0, 0.0, [steady_target(gap_m=200.0, speed_mps=30.0)], 40.0, SPACING)
        assert abs(cmd.accel_request_mps2 - last) <= CAR.limits.max_jerk_mps3 * DT + 1e-9
        assert -CAR.limits.max_decel_mps2 <= cmd.accel_request_mps2 <= CAR.limits.max_accel_mps2
        last = cmd.accel_request_mps2


def test_a_stopped_vehicle_close_ahead_triggers_emergency_braking_beyond_the_comfort_limit():
    ctrl = LongitudinalController(CAR)
    stopped = steady_target(object_id=4, gap_m=25.0, speed_mps=0.0, v2v_age_s=None, accel_mps2=None)
    cmd = run(ctrl, 25, [stopped])
    assert cmd.emergency_brake
    assert cmd.mode == M.LONGITUDINAL_MODE_EMERGENCY_BRAKE
    assert cmd.target_object_id == 4
    assert cmd.accel_request_mps2 == pytest.approx(-CAR.limits.emergency_decel_mps2)


def test_a_slower_virtual_target_close_ahead_in_the_other_lane_is_left_to_the_comfort_laws():
    # The merge's case: 2.5 m behind a gap maker in the next lane, 5.5 m/s faster; TTC 0.45 s by the gap alone.
    beside = steady_target(object_id=4, gap_m=2.5, speed_mps=16.7, role=planner_pb2.TARGET_ROLE_VIRTUAL, in_path=False)
    cmd = run(LongitudinalController(CAR), 60, [beside], speed_mps=22.2)
    assert not cmd.emergency_brake and cmd.target_object_id == 4
    assert cmd.accel_request_mps2 == pytest.approx(-CAR.limits.max_decel_mps2)
    in_our_lane = steady_target(object_id=4, gap_m=2.5, speed_mps=16.7, role=planner_pb2.TARGET_ROLE_VIRTUAL)
    assert run(LongitudinalController(CAR), 25, [in_our_lane], speed_mps=22.2).emergency_brake


def test_a_predecessor_requesting_hard_braking_starts_emergency_braking_before_its_brakes_bite():
    # 17 m at 22 m/s behind a car still measured at 0 m/s2 whose controller now asks for -5 m/s2 (iCLCM).
    requesting = steady_target(gap_m=17.0, speed_mps=22.0, accel_mps2=0.0, intended_accel_mps2=-5.0)
    cmd = LongitudinalController(CAR).step(0.0, 22.0, 0.0, [requesting], 30.0, SPACING)
    assert cmd.emergency_brake and cmd.mode == M.LONGITUDINAL_MODE_EMERGENCY_BRAKE
    measured_only = steady_target(gap_m=17.0, speed_mps=22.0, accel_mps2=0.0)
    assert not LongitudinalController(CAR).step(0.0, 22.0, 0.0, [measured_only], 30.0, SPACING).emergency_brake


def test_the_selected_reference_laws_can_be_swapped_in_by_configuration():
    ctrl = LongitudinalController(CAR, cacc_law=CaccLaw.PLOEG, acc_law=AccLaw.RAJAMANI, speed_law=SpeedLaw.DRIVERTIVE)
    assert run(ctrl, 3, [steady_target()]).mode == M.LONGITUDINAL_MODE_CACC
    assert ctrl.step(10.0, 20.0, 0.0, [], 25.0).mode == M.LONGITUDINAL_MODE_CRUISE


def test_an_invalid_target_is_skipped_and_counted_not_fatal():
    ctrl = LongitudinalController(CAR)
    cmd = ctrl.step(0.0, 20.0, 0.0, [steady_target(gap_m=math.nan)], 25.0, SPACING)
    assert cmd.mode == M.LONGITUDINAL_MODE_CRUISE
    assert ctrl.rejected_inputs == 1
    assert "gap_m" in ctrl.last_rejection


def test_a_non_finite_ego_speed_raises_an_error_naming_it():
    with pytest.raises(ValueError, match="ego_speed_mps"):
        LongitudinalController(CAR).step(0.0, math.inf, 0.0, [], 25.0)


def test_the_planner_spacing_policy_message_is_accepted_and_a_zero_time_gap_means_the_policy_s_cacc_gap():
    ctrl = LongitudinalController(CAR)
    far = steady_target(gap_m=60.0)
    cmd = ctrl.step(0.0, 20.0, 0.0, [far], 30.0, planner_pb2.SpacingPolicy(standstill_m=5.0, time_gap_s=0.6))
    assert cmd.time_gap_s == pytest.approx(0.6)
    cmd = LongitudinalController(CAR).step(0.0, 20.0, 0.0, [far], 30.0, planner_pb2.SpacingPolicy(standstill_m=5.0))
    assert cmd.time_gap_s == pytest.approx(SPACING_POLICY.cacc_time_gap_s)


def test_the_command_fills_the_control_command_message():
    cmd = run(LongitudinalController(CAR), 3, [steady_target(object_id=12)])
    msg = cmd.fill(control_pb2.ControlCommand())
    assert msg.longitudinal_mode == M.LONGITUDINAL_MODE_CACC
    assert msg.target_object_id == 12
    assert msg.accel_request_mps2 == pytest.approx(cmd.accel_request_mps2)
    assert msg.response_time_constant_s == pytest.approx(CAR.engine_lag_s)


def test_at_standstill_behind_a_stopped_vehicle_the_mode_is_standstill():
    ctrl = LongitudinalController(CAR)
    stopped = steady_target(gap_m=6.0, speed_mps=0.0, accel_mps2=0.0)
    cmd = run(ctrl, 5, [stopped], speed_mps=0.0)
    assert cmd.mode == M.LONGITUDINAL_MODE_STANDSTILL
    assert not cmd.emergency_brake


@pytest.mark.parametrize("law", list(CaccLaw), ids=lambda law: law.value)
def test_a_cooperative_law_taking_over_starts_from_the_applied_command(law):
    ctrl = LongitudinalController(CAR, cacc_law=law)
    cmd = run(ctrl, 100, [], speed_mps=20.0, desired_mps=21.0)
    applied = cmd.accel_request_mps2
    # A predecessor pulling away, accelerating: the law wants more than cruise, yet starts where cruise was.
    ahead = steady_target(object_id=5, gap_m=30.0, speed_mps=22.0, accel_mps2=1.0)
    cmd = ctrl.step(100 * DT, 20.0, applied, [ahead], 21.0, SPACING)
    # One 20 ms step of the law's own dynamics away from the applied command (the law alone would ask ~9 m/s2).
    assert cmd.law_outputs_mps2["LONGITUDINAL_MODE_CACC:5"] == pytest.approx(applied, abs=0.2)


def test_cruise_taking_over_after_an_emergency_brake_recovers_the_speed_instead_of_braking_on():
    """A car passing close in the other direction read as a target for half a second: the car brakes hard,
    then cruise takes over and brings it back to its speed without stopping."""
    from coopdrive.services.control.longitudinal import Target

    controller = LongitudinalController(CAR)
    speed_mps, accel_mps2, speeds = 11.9, 0.0, []
    for step in range(int(20.0 / 0.02)):
        now_s = step * 0.02
        close_call = [Target(object_id=7, gap_m=2.0, speed_mps=0.0)] if 1.0 <= now_s < 1.5 else []
        command = controller.step(now_s, speed_mps, accel_mps2, close_call, 13.9)
        accel_mps2 += (command.accel_request_mps2 - accel_mps2) * 0.02 / CAR.engine_lag_s
        speed_mps = max(0.0, speed_mps + accel_mps2 * 0.02)
        speeds.append(speed_mps)
    assert min(speeds[75:]) < 11.0  # it did brake for the close call
    assert min(speeds) > 3.0
    assert speeds[-1] == pytest.approx(13.9, abs=0.3)
