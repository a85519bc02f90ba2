"""The emergency path (eq. E1-E4) against hand-computed kinematics: when it starts, how hard it brakes, when it lets go."""

import math

import pytest

from coopdrive.services.control.longitudinal.emergency import EmergencyBrake, EmergencyTarget, min_gap_within_m
from coopdrive.services.control.profiles import CAR

# CAR: comfort decel 2 m/s2, stop margin 2 m + release margin 1 m = 3 m release gap, horizon 2.5 s.
RELEASE_GAP_M = CAR.limits.stop_margin_m + CAR.limits.release_margin_m


def test_time_to_collision_is_the_gap_over_the_closing_speed_and_infinite_when_opening():
    eb = EmergencyBrake(CAR.limits)
    assert eb.ttc_s(20.0, 20.0, 10.0) == pytest.approx(2.0)
    assert eb.ttc_s(20.0, 10.0, 20.0) == math.inf


def test_behind_a_steady_slower_target_the_required_deceleration_is_the_constant_speed_case():
    # room 20 - 3 = 17 m, closing 10 m/s: -100 / 34
    assert EmergencyBrake(CAR.limits).required_accel_mps2(20.0, 20.0, 10.0, 0.0) == pytest.approx(-100.0 / 34.0)


def test_behind_a_hard_braking_predecessor_at_equal_speed_both_stop_and_the_gap_is_smallest_at_the_end():
    # room 22.5 - 3 = 19.5 m, predecessor stops in 22^2 / 7 = 69.14 m: -22^2 / (2 (19.5 + 69.14)) = -2.730 (E2a)
    need = EmergencyBrake(CAR.limits).required_accel_mps2(22.5, 22.0, 22.0, -3.5)
    assert need == pytest.approx(-(22.0**2) / (2 * (19.5 + 22.0**2 / 7.0)))
    assert need == pytest.approx(-2.730, abs=1e-3)


def test_closing_fast_on_a_braking_predecessor_the_ego_must_brake_harder_and_match_speeds_first():
    # room 13 - 3 = 10 m; E2a would need -400 / 70 = -5.7, harder than the predecessor's -2, so E2b: -2 - 100 / 20
    assert EmergencyBrake(CAR.limits).required_accel_mps2(13.0, 20.0, 10.0, -2.0) == pytest.approx(-7.0)


def test_a_closing_target_inside_the_release_gap_needs_unbounded_braking():
    assert EmergencyBrake(CAR.limits).required_accel_mps2(2.5, 10.0, 5.0, 0.0) == -math.inf


def test_the_gap_minimum_under_constant_decelerations_is_found_where_speeds_meet_or_at_the_horizon():
    # Both at 20 m/s, ego -2 and predecessor -3.5 for 3 s: the gap loses 1.5 * 9 / 2 = 6.75 m.
    assert min_gap_within_m(20.0, 20.0, -2.0, 20.0, -3.5, 3.0) == pytest.approx(13.25)
    # Ego 20 m/s at -2 behind a steady 10 m/s: speeds meet at 5 s after the gap lost 25 m, then it opens again.
    assert min_gap_within_m(20.0, 20.0, -2.0, 10.0, 0.0, 10.0) == pytest.approx(-5.0)
    # The predecessor stops after 1 s and 2 m; the ego, still rolling at 4 m/s, has covered 21 m at 3 s.
    assert min_gap_within_m(20.0, 10.0, -2.0, 4.0, -4.0, 3.0) == pytest.approx(1.0)


def test_braking_starts_when_comfort_braking_cannot_keep_the_margin_and_releases_with_hysteresis():
    eb = EmergencyBrake(CAR.limits)
    # 20 m/s behind 10 m/s at 20 m: within 2.5 s at -2 the gap would fall to 1.25 m.
    first = eb.step(20.0, [EmergencyTarget(7, 20.0, 10.0, 0.0)])
    assert first.active and first.object_id == 7
    assert first.accel_mps2 == pytest.approx(-100.0 / 34.0)
    assert eb.step(20.0, [EmergencyTarget(7, 12.5, 15.0, 0.0)]).active  # TTC 2.5 s, still below the 3 s release
    assert not eb.step(20.0, [EmergencyTarget(7, 40.0, 15.0, 0.0)]).active  # TTC 8 s, comfort braking keeps 33.75 m


def test_a_brief_predecessor_braking_beyond_comfort_at_a_normal_gap_stays_with_the_comfort_laws():
    # The string scenario's +-10 km/h at 0.2 Hz brakes at 3.5 m/s2; at 0.7 s x 22 m/s + 6 m the gap absorbs it.
    decision = EmergencyBrake(CAR.limits).step(22.0, [EmergencyTarget(3, 21.5, 22.0, -3.5)])
    assert not decision.active


def test_the_emergency_deceleration_is_never_weaker_than_comfort_nor_stronger_than_the_emergency_limit():
    eb = EmergencyBrake(CAR.limits)
    # Closing at 5 m/s inside the release gap: unbounded need, clipped to the emergency limit.
    clipped = eb.step(10.0, [EmergencyTarget(1, 2.5, 5.0, 0.0)])
    assert clipped.accel_mps2 == pytest.approx(-CAR.limits.emergency_decel_mps2)
    # Held by hysteresis (TTC 2.5 s) while only -25 / 19 m/s2 is needed: braking stays at the comfort limit.
    held = eb.step(20.0, [EmergencyTarget(1, 12.5, 15.0, 0.0)])
    assert held.active
    assert held.accel_mps2 == pytest.approx(-CAR.limits.max_decel_mps2)


def test_standing_close_behind_a_stopped_vehicle_is_not_an_emergency():
    eb = EmergencyBrake(CAR.limits)
    eb.active = True
    assert not eb.step(0.0, [EmergencyTarget(1, 2.2, 0.0, 0.0)]).active


def test_a_predecessor_reporting_braking_as_hard_as_an_emergency_brake_is_matched_at_once():
    # 17 m at 22 m/s, both at speed: the horizon alone would wait, a 4+ m/s2 predecessor is not waited for (E4).
    decision = EmergencyBrake(CAR.limits).step(22.0, [EmergencyTarget(5, 17.0, 22.0, -5.0, accel_reported=True)])
    assert decision.active and decision.object_id == 5
    assert decision.accel_mps2 == pytest.approx(-5.0)


def test_a_predecessor_braking_just_below_the_hard_braking_threshold_is_left_to_the_horizon():
    assert not EmergencyBrake(CAR.limits).step(22.0, [EmergencyTarget(5, 17.0, 22.0, -3.9, accel_reported=True)]).active


def test_a_hard_deceleration_we_only_estimate_from_our_sensors_is_left_to_the_horizon():
    # The same -5 m/s2, differentiated from a young radar track's speeds rather than reported over V2V.
    assert not EmergencyBrake(CAR.limits).step(22.0, [EmergencyTarget(5, 17.0, 22.0, -5.0)]).active


def test_a_stopped_predecessor_still_reporting_its_last_deceleration_is_not_hard_braking():
    eb = EmergencyBrake(CAR.limits)
    assert not eb.step(0.0, [EmergencyTarget(5, 3.5, 0.0, -5.0, accel_reported=True)]).active


def test_standing_behind_a_standing_predecessor_whose_speeds_jitter_above_zero_is_not_hard_braking():
    # Measured speeds of two standing cars read a few cm/s; the predecessor's CAM still says -5 m/s2.
    eb = EmergencyBrake(CAR.limits)
    assert not eb.step(0.04, [EmergencyTarget(5, 11.8, 0.06, -5.0, accel_reported=True)]).active
