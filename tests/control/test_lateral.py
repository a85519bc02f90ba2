"""Lateral laws against their equations, the quintic lane change, and the closed-loop lane change."""

import math

import pytest
from control_sim import DT_S, run_lane_change

from coopdrive.services.control.lateral import LateralController, LateralLaw, PathState
from coopdrive.services.control.lateral.lane_change import QuinticTransition
from coopdrive.services.control.lateral.pd import HeudiasycPd
from coopdrive.services.control.lateral.pure_pursuit import PurePursuit
from coopdrive.services.control.lateral.stanley import Stanley
from coopdrive.services.control.profiles import CAR, LateralGains
from coopdrive.v1 import control_pb2

GAINS = LateralGains(alpha1_1ps2=0.36, alpha2_1ps=1.2, stanley_gain=1.0, stanley_softening_mps=1.0,
                     pure_pursuit_lookahead_time_s=1.5, pure_pursuit_min_lookahead_m=5.0)
WB = 2.7
# 10 m/s, 0.5 m right of the reference, heading 0.02 rad to the left, straight lane.
STATE = PathState(speed_mps=10.0, lateral_offset_m=-0.5, heading_error_rad=0.02)


def test_heudiasyc_pd_is_eq_10_on_a_straight_reference():
    # delta = L/v^2 (alpha1 e_l + alpha2 v e_theta) = 2.7/100 (0.36*0.5 + 1.2*10*(-0.02))
    assert HeudiasycPd(GAINS, WB).steering_rad(STATE) == pytest.approx(0.027 * (0.18 - 0.24))


def test_heudiasyc_pd_adds_the_reference_acceleration_and_the_curvature_feedforward():
    p = PathState(10.0, 0.0, 0.0, curvature_1pm=0.002, reference_offset_m=0.0, reference_rate_mps=0.5, reference_accel_mps2=0.3)
    # eq. 9: L/v^2 (alpha2 * 0.5 + 0.3) + atan(L kappa)
    assert HeudiasycPd(GAINS, WB).steering_rad(p) == pytest.approx(0.027 * (0.6 + 0.3) + math.atan(WB * 0.002))


def test_heudiasyc_pd_floors_the_speed_to_avoid_the_standstill_singularity():
    slow = PathState(0.0, -0.5, 0.0)
    assert HeudiasycPd(GAINS, WB).steering_rad(slow) == pytest.approx(WB / GAINS.min_speed_mps**2 * 0.36 * 0.5)


def test_stanley_corrects_heading_and_front_axle_cross_track_error():
    front = -0.5 + WB * math.sin(0.02)
    expected = -0.02 + math.atan2(1.0 * (0.0 - front), 1.0 + 10.0)
    assert Stanley(GAINS, WB).steering_rad(STATE) == pytest.approx(expected)


def test_pure_pursuit_steers_onto_the_arc_through_the_look_ahead_point():
    ld = 15.0  # 1.5 s * 10 m/s
    alpha = math.atan2(0.0 - (-0.5), ld) - 0.02
    law = PurePursuit(GAINS, WB)
    assert law.lookahead_m(10.0) == pytest.approx(ld)
    assert law.steering_rad(STATE) == pytest.approx(math.atan(2 * WB * math.sin(alpha) / ld))


def test_the_quintic_moves_between_offsets_with_zero_rate_and_acceleration_at_both_ends():
    q = QuinticTransition(start_time_s=1.0, duration_s=5.0, start_offset_m=-3.5, end_offset_m=0.0)
    assert q.sample(1.0) == pytest.approx((-3.5, 0.0, 0.0))
    assert q.sample(6.0) == pytest.approx((0.0, 0.0, 0.0))
    # midpoint: -3.5 + 3.5 (10/8 - 15/16 + 6/32) = -1.75, peak rate 1.875 D / T
    y, dy, ddy = q.sample(3.5)
    assert (y, dy, ddy) == pytest.approx((-1.75, 1.875 * 3.5 / 5.0, 0.0), abs=1e-9)


def test_the_quintic_starts_from_the_current_lateral_speed():
    q = QuinticTransition(0.0, 4.0, 0.0, 3.5, start_rate_mps=0.4)
    assert q.sample(0.0)[1] == pytest.approx(0.4)
    assert q.sample(4.0 - 1e-9) == pytest.approx((3.5, 0.0, 0.0), abs=1e-6)


def test_a_jump_of_the_target_lane_starts_a_lane_change_and_steers_within_the_limits():
    ctrl = LateralController(CAR)
    ctrl.step(0.0, 20.0, 0.0, 0.0)
    cmd = ctrl.step(DT_S, 20.0, -3.5, 0.0)
    assert cmd.mode == control_pb2.LATERAL_MODE_LANE_CHANGE
    assert cmd.reference_offset_m == pytest.approx(-3.5, abs=1e-3)
    assert abs(cmd.steering_angle_rad) <= CAR.steering.max_rate_radps * DT_S * 2 + 1e-12
    assert cmd.curvature_1pm == pytest.approx(math.tan(cmd.steering_angle_rad) / CAR.wheelbase_m)


def test_the_steering_angle_is_capped_by_the_lateral_acceleration_limit():
    ctrl = LateralController(CAR.model_copy(update={"steering": CAR.steering.model_copy(update={"max_rate_radps": 100.0})}))
    cmd = ctrl.step(0.0, 30.0, -1.0, -0.3)
    assert abs(cmd.steering_angle_rad) == pytest.approx(math.atan(CAR.wheelbase_m * CAR.steering.max_lateral_accel_mps2 / 900.0))


def test_a_non_finite_lateral_offset_raises_an_error_naming_it():
    with pytest.raises(ValueError, match="lateral_offset_m"):
        LateralController(CAR).step(0.0, 10.0, math.nan, 0.0)


@pytest.mark.parametrize("law", list(LateralLaw), ids=lambda law: law.value)
@pytest.mark.parametrize("speed_kmh", [40, 80])
def test_a_lane_change_completes_within_10_s_gently_and_without_overshoot(law, speed_kmh):
    run = run_lane_change(law, speed_kmh / 3.6, switch_at_s=2.0, duration_s=16.0)
    after = [(t, y, ay) for t, y, ay in zip(run.times_s, run.offsets_m, run.lateral_accels_mps2) if t >= 2.0]
    settled = [t for t, y, _ in after if abs(y) < 0.1]
    done_s = next(t for t in settled if all(abs(y) < 0.1 for tt, y, _ in after if tt >= t)) - 2.0
    assert done_s < 10.0
    assert max(abs(ay) for _, _, ay in after) < 2.0
    assert max(y for _, y, _ in after) < 0.3  # approaching 0 from -3.5: positive is overshoot


@pytest.mark.parametrize("law", list(LateralLaw), ids=lambda law: law.value)
def test_curvature_feedforward_keeps_the_lane_on_a_500_m_curve(law):
    run = run_lane_change(law, 80 / 3.6, lane_width_m=0.0, duration_s=10.0, curvature_1pm=1 / 500)
    assert max(abs(y) for y in run.offsets_m) < 0.1
