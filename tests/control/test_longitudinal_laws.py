"""Each longitudinal law against outputs computed by hand from its equation."""

import math
from dataclasses import replace

import pytest

from coopdrive.services.control.longitudinal.acc import RadarAcc, RajamaniAcc
from coopdrive.services.control.longitudinal.cacc import LagCompensatedCacc
from coopdrive.services.control.longitudinal.cruise import CruisePi
from coopdrive.services.control.longitudinal.dcacc import RangeRateAccelEstimator
from coopdrive.services.control.longitudinal.drivertive import DrivertiveSpeed, drivertive_follow_accel_mps2
from coopdrive.services.control.longitudinal.ploeg import PloegCacc
from coopdrive.services.control.longitudinal.shaper import CommandShaper
from coopdrive.services.control.longitudinal.types import FollowInput
from coopdrive.services.control.profiles import CAR, CaccGains, DcaccGains, PloegGains

DT = 0.02
# gap 20 m, v 20 m/s, a 0.5 m/s2, v_p 21 m/s, a_p 1 m/s2, r 6 m, h 0.5 s: e = 4 m, e' = 0.75 m/s
CLOSE = FollowInput(gap_m=20.0, ego_speed_mps=20.0, ego_accel_mps2=0.5, pred_speed_mps=21.0,
                    pred_accel_mps2=1.0, standstill_m=6.0, time_gap_s=0.5)
# gap 40 m, v 20 m/s, a -0.5 m/s2, v_p 18 m/s, r 6 m, h 1.5 s: e = 4 m
RADAR = FollowInput(gap_m=40.0, ego_speed_mps=20.0, ego_accel_mps2=-0.5, pred_speed_mps=18.0,
                    pred_accel_mps2=0.0, standstill_m=6.0, time_gap_s=1.5)
NO_FEEDFORWARD = CAR.model_copy(update={"cruise": CAR.cruise.model_copy(update={"resistance_feedforward": False})})


def test_the_spacing_error_and_its_rate_follow_the_constant_time_gap_policy():
    assert CLOSE.desired_gap_m == pytest.approx(16.0)
    assert CLOSE.spacing_error_m == pytest.approx(4.0)
    assert CLOSE.spacing_error_rate_mps == pytest.approx(0.75)


def test_ploeg_integrates_its_filter_equation_one_euler_step():
    law = PloegCacc(PloegGains())
    law.reset(0.3, CLOSE)
    # u' = (1/0.5)(-0.3 + 0.2*4 + 0.7*0.75 + 1.0) = 4.05  ->  u = 0.3 + 0.02*4.05
    assert law.step(DT, CLOSE) == pytest.approx(0.381)


def test_our_cacc_adds_the_lag_compensated_feedforward_to_the_spacing_pd():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5), engine_lag_s=0.3)
    z = 1.0 - math.exp(-DT / 0.5)  # filter state after one exact step from 0 towards a_p = 1
    expected = 0.6 * 1.0 + 0.4 * z + 0.3 * 4.0 + 2.5 * 0.75
    assert law.step(DT, CLOSE) == pytest.approx(expected)
    assert expected == pytest.approx(3.6906842, abs=1e-6)


def test_ploeg_takes_the_predecessors_request_over_its_measured_acceleration():
    law = PloegCacc(PloegGains())
    law.reset(0.3, CLOSE)
    # u' = (1/0.5)(-0.3 + 0.2*4 + 0.7*0.75 + 2.0) = 6.05
    assert law.step(DT, replace(CLOSE, pred_intended_accel_mps2=2.0)) == pytest.approx(0.3 + 0.02 * 6.05)


def test_our_cacc_feeds_forward_the_predecessors_request_through_the_time_gap_filter_alone():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5, request_lead_s=0.0), engine_lag_s=0.3)
    law.reset(10.0, replace(CLOSE, pred_intended_accel_mps2=0.0))  # above the law: no bump offset
    z_u = 2.0 * (1.0 - math.exp(-DT / 0.5))  # eq. C3, one exact step from 0 towards u_p = 2; a_p = 1 is unused
    assert law.step(DT, replace(CLOSE, pred_intended_accel_mps2=2.0)) == pytest.approx(z_u + 0.3 * 4.0 + 2.5 * 0.75)


def test_our_cacc_leads_the_request_feedforward_by_the_request_lead():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5, request_lead_s=0.1), engine_lag_s=0.3)
    law.reset(10.0, replace(CLOSE, pred_intended_accel_mps2=0.0))
    z_u = 2.0 * (1.0 - math.exp(-DT / 0.5))  # eq. C3 as above
    lead = z_u + 0.1 / 0.5 * (2.0 - z_u)  # eq. C5: z_u + (theta / h) (u_p - z_u)
    assert law.step(DT, replace(CLOSE, pred_intended_accel_mps2=2.0)) == pytest.approx(lead + 0.3 * 4.0 + 2.5 * 0.75)


def test_our_cacc_filters_its_spacing_pd_with_the_feedback_time_constant():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5, feedback_time_constant_s=0.2), engine_lag_s=0.3)
    at_gap = replace(CLOSE, gap_m=16.0, pred_speed_mps=20.5)  # e = 0, e' = 0.5 - 0.25 = 0.25: PD 0.625
    law.reset(10.0, at_gap)
    law.step(DT, at_gap)
    z = law.filtered_accel_mps2
    z_next = z + (1.0 - math.exp(-DT / 0.5)) * (1.0 - z)
    pd = 0.625 + (1.0 - math.exp(-DT / 0.2)) * (3.075 - 0.625)  # eq. C4: one exact step from 0.625 to 3.075
    assert law.step(DT, CLOSE) == pytest.approx(0.6 * 1.0 + 0.4 * z_next + pd)


def test_our_cacc_continues_from_the_measured_feedforward_when_a_request_first_arrives():
    law = LagCompensatedCacc(CaccGains(), engine_lag_s=0.3)
    steady = FollowInput(16.0, 20.0, 0.8, 20.4, 0.8, 6.0, 0.5)
    law.reset(0.8, steady)
    for _ in range(10):
        law.step(DT, steady)
    assert law.step(DT, replace(steady, pred_intended_accel_mps2=0.8)) == pytest.approx(0.8)


def test_our_cacc_passes_a_steady_predecessor_acceleration_through_unchanged():
    law = LagCompensatedCacc(CaccGains(), engine_lag_s=0.4)
    steady = FollowInput(16.0, 20.0, 0.8, 20.4, 0.8, 6.0, 0.5)  # e = 0, e' = 20.4 - 20 - 0.5*0.8 = 0
    law.reset(0.8, steady)
    assert law.step(DT, steady) == pytest.approx(0.8)


def test_our_cacc_starts_bumplessly_when_it_would_accelerate_harder_than_the_current_command():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5, bump_time_constant_s=1.0), engine_lag_s=0.3)
    law.reset(0.0, CLOSE)  # law would command 1.0 + 3.075 = 4.075
    assert law.step(DT, CLOSE) == pytest.approx(4.075 * (1 - math.exp(-DT)))


def test_our_cacc_never_delays_braking_for_bumpless_transfer():
    law = LagCompensatedCacc(CaccGains(kp_1ps2=0.3, kd_1ps=2.5), engine_lag_s=0.3)
    law.reset(10.0, CLOSE)
    assert law.step(DT, CLOSE) == pytest.approx(4.075)


def test_rajamani_acc_matches_its_equation():
    # -(1/1.5)[(20 - 18) + 0.1(-40 + 1.5*20 + 6)] = -(1/1.5)(2 - 0.4)
    assert RajamaniAcc(CAR.rajamani).step(DT, RADAR) == pytest.approx(-1.0666667, abs=1e-6)


def test_our_acc_matches_its_equation():
    # 1.0*(18 - 20) + 0.15*4 - 0.2*1.5*(-0.5)
    assert RadarAcc(CAR.acc).step(DT, RADAR) == pytest.approx(-1.25)


def test_the_range_rate_estimator_recovers_a_constant_predecessor_deceleration():
    est = RangeRateAccelEstimator(DcaccGains(estimator_window_s=0.4, estimator_min_samples=5))
    for k in range(40):
        t = k * DT
        ego = 20.0 + 0.3 * t
        pred = 22.0 - 1.5 * t
        est.observe(t, ego, pred - ego)
    assert est.estimate_mps2() == pytest.approx(-1.5)


def test_the_range_rate_estimator_gives_nothing_until_its_window_has_enough_samples():
    est = RangeRateAccelEstimator(DcaccGains(estimator_min_samples=5))
    for k in range(4):
        est.observe(k * DT, 20.0, 0.0)
    assert est.estimate_mps2() is None


def test_resistance_feedforward_is_rolling_plus_aerodynamic_drag_over_mass():
    # (0.5*1.225*0.7*10^2 + 0.012*1500*9.81) / 1500
    assert CAR.resistance_accel_mps2(10.0) == pytest.approx(219.455 / 1500)


def test_cruise_pi_follows_its_reference_model_one_step_by_hand():
    pi = CruisePi(NO_FEEDFORWARD)
    pi.engage(0.0, 10.0)
    # a_ref = 1 m/s3 * 0.02 s; v_ref = 10.0004; u = a_ref + tau*jerk + kp*e + ki*e*dt, tau = 0.3 s
    expected = 0.02 + 0.3 * 1.0 + 0.8 * 0.0004 + 0.15 * 0.0004 * DT
    assert pi.step(DT, 10.0, 20.0) == pytest.approx(expected)


def test_cruise_pi_back_calculates_its_integrator_towards_the_applied_command():
    pi = CruisePi(NO_FEEDFORWARD)
    pi.engage(0.0, 10.0)
    out = pi.step(DT, 10.0, 20.0)
    before = pi.integral_mps2
    pi.track(DT, 0.1)
    assert pi.integral_mps2 - before == pytest.approx(DT * (0.1 - out) / 1.0)


def test_a_disengaged_cruise_offers_a_governor_that_binds_only_near_the_set_speed():
    pi = CruisePi(NO_FEEDFORWARD)
    assert pi.step(DT, 10.0, 20.0) == pytest.approx(CAR.limits.max_accel_mps2)  # (20 - 10) / 1 s, capped at 2
    assert pi.step(DT, 19.4, 20.0) == pytest.approx(0.6)  # (eq. S4)
    assert pi.step(DT, 30.0, 20.0) == pytest.approx(-CAR.limits.max_decel_mps2)


def test_drivertive_gain_adapts_to_speed_when_accelerating_and_is_constant_when_braking():
    law = DrivertiveSpeed(NO_FEEDFORWARD)
    assert law.step(DT, 10.0, 12.0) == pytest.approx((0.2 + 0.04 * 10.0) * 2.0)
    assert law.step(DT, 10.0, 8.0) == pytest.approx(1.0 * -2.0)


def test_drivertive_follow_law_is_zero_at_the_desired_gap_and_deadbeat_off_it():
    at_gap = drivertive_follow_accel_mps2(30.0, 20.0, 20.0, 0.0, 10.0, 1.0, 0.05)
    assert at_gap == pytest.approx(0.0, abs=1e-9)
    one_metre_long = drivertive_follow_accel_mps2(31.0, 20.0, 20.0, 0.0, 10.0, 1.0, 0.05)
    assert one_metre_long == pytest.approx(1.0 / (0.05 * 1.025))


def test_the_shaper_clips_to_comfort_and_limits_jerk_but_the_emergency_path_goes_further():
    shaper = CommandShaper(CAR.limits)
    assert shaper.step(DT, 3.0) == pytest.approx(2.5 * DT)
    shaper.reset(-2.0)
    assert shaper.step(DT, -8.0) == pytest.approx(-2.0)
    assert shaper.step(DT, -8.0, emergency=True) == pytest.approx(-2.0 - 30.0 * DT)


def test_a_brake_beyond_comfort_is_released_at_the_emergency_jerk_down_to_the_comfort_limit_then_at_comfort():
    shaper = CommandShaper(CAR.limits)
    shaper.reset(-6.0)
    steps = [shaper.step(DT, 0.0) for _ in range(10)]
    emergency_steps = math.ceil((6.0 - CAR.limits.max_decel_mps2) / (CAR.limits.emergency_jerk_mps3 * DT))
    assert steps[emergency_steps - 1] == pytest.approx(-CAR.limits.max_decel_mps2)
    assert steps[emergency_steps] == pytest.approx(-CAR.limits.max_decel_mps2 + CAR.limits.max_jerk_mps3 * DT)
    assert steps[0] == pytest.approx(-6.0 + CAR.limits.emergency_jerk_mps3 * DT)
