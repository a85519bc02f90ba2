import math

import numpy as np
import pytest
from scipy.integrate import quad

from coopdrive.services.geolocation.ekf import GeolocationEkf, UpdateKind, gnss_position_std_m
from coopdrive.services.geolocation.frames import LeverArm
from coopdrive.services.geolocation.motion_models import (
    ACCEL, ACCEL_BIAS, STATE_DIM, YAW_RATE, YAW_RATE_BIAS, CtraModel, KinematicBicycleModel, ProcessNoise,
)
from coopdrive.v1 import gnss_pb2

# [E, N, heading, v, yaw rate, a], the inertial unit's yaw-rate and acceleration biases and the fixes' correlated
# error and their stamps' error (none here).
STATE = np.array([10.0, 5.0, 0.3, 20.0, 0.05, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0])


def started_ekf(model=None) -> GeolocationEkf:
    ekf = GeolocationEkf(model or CtraModel(ProcessNoise()))
    ekf.initialise(0.0, STATE, np.diag([0.01, 0.01, 1e-4, 0.01, 1e-4, 0.1, 1e-4, 1e-2, 0.0, 0.0, 0.0]))
    return ekf


@pytest.mark.parametrize(("fix_mode", "expected_m"), [
    (gnss_pb2.FIX_MODE_RTK_FIXED, 0.01), (gnss_pb2.FIX_MODE_RTK_FLOAT, 0.5), (gnss_pb2.FIX_MODE_DGPS, 1.0),
    (gnss_pb2.FIX_MODE_SBAS, 3.0), (gnss_pb2.FIX_MODE_SINGLE, 5.0)])
def test_without_gst_the_fix_sigma_comes_from_the_heudiasyc_table(fix_mode, expected_m):
    assert gnss_position_std_m(fix_mode) == (expected_m, expected_m)


def test_gst_sigmas_are_used_but_never_below_the_table_value():
    assert gnss_position_std_m(gnss_pb2.FIX_MODE_RTK_FIXED, 0.03, 0.002) == (0.03, 0.01)
    assert gnss_position_std_m(gnss_pb2.FIX_MODE_NO_FIX) is None


def test_ctra_follows_the_exact_constant_turn_rate_and_acceleration_path():
    ekf = started_ekf()
    ekf.predict_to(0.1)
    # Exact CTRA: position = integral of (v0 + a t) (cos, sin)(heading0 + yaw_rate t) dt.
    speed, heading = (lambda t: 20.0 + 0.5 * t), (lambda t: 0.3 + 0.05 * t)
    east = 10.0 + quad(lambda t: speed(t) * math.cos(heading(t)), 0.0, 0.1)[0]
    north = 5.0 + quad(lambda t: speed(t) * math.sin(heading(t)), 0.0, 0.1)[0]
    assert ekf.x[:2] == pytest.approx([east, north], abs=1e-5)
    assert ekf.x[2:] == pytest.approx([0.305, 20.05, 0.05, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0])


@pytest.mark.parametrize("model", [CtraModel(ProcessNoise()), KinematicBicycleModel(ProcessNoise(), 2.7)])
def test_the_model_jacobian_matches_finite_differences(model):
    steering_rad = 0.04
    _, F, _ = model.step(STATE, 0.02, steering_rad)
    numeric = np.zeros((STATE_DIM, STATE_DIM))
    for j in range(STATE_DIM):
        step = np.zeros(STATE_DIM)
        step[j] = 1e-6
        numeric[:, j] = (model.step(STATE + step, 0.02, steering_rad)[0]
                         - model.step(STATE - step, 0.02, steering_rad)[0]) / 2e-6
    assert F == pytest.approx(numeric, abs=1e-6)


def test_the_bicycle_model_turns_at_v_tan_delta_over_wheelbase():
    model = KinematicBicycleModel(ProcessNoise(), wheelbase_m=2.7)
    x, _, _ = model.step(np.array([0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 0.01, math.atan(0.27))
    assert x[4] == pytest.approx(1.0)
    assert x[2] == pytest.approx(0.01)


def test_a_consistent_fix_is_fused_and_pulls_the_estimate():
    ekf = started_ekf()
    assert ekf.update_gnss_position(10.1, 5.0, 0.1, 0.1, LeverArm())
    assert 10.0 < ekf.x[0] < 10.1
    assert ekf.accepted[UpdateKind.GNSS_POSITION] == 1


def test_a_fix_outside_the_chi_square_gate_is_rejected_and_counted():
    ekf = started_ekf()
    assert not ekf.update_gnss_position(13.0, 9.0, 0.05, 0.05, LeverArm())
    assert ekf.x == pytest.approx(STATE)
    assert ekf.rejected[UpdateKind.GNSS_POSITION] == 1
    assert ekf.last_nis > ekf.gate(2)


def test_the_antenna_lever_arm_is_part_of_the_measurement():
    ekf = started_ekf()
    arm = LeverArm(x_m=1.0)
    antenna = arm.antenna_position(10.0, 5.0, 0.3)
    assert ekf.update_gnss_position(*antenna, 0.05, 0.05, arm)
    assert ekf.x[:2] == pytest.approx([10.0, 5.0], abs=1e-9)


def test_predicting_ahead_does_not_move_the_filter():
    ekf = started_ekf()
    x, P = ekf.predicted(1.0)
    assert ekf.time_s == 0.0 and ekf.x == pytest.approx(STATE)
    assert x[0] > STATE[0] and P[0, 0] > 0.01


def test_a_heading_across_the_wrap_pulls_the_estimate_the_short_way():
    ekf = GeolocationEkf()
    ekf.initialise(0.0, np.array([0.0, 0.0, math.pi - 0.01, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
                   np.diag([0.01, 0.01, 1e-2, 0.01, 0.1, 1, 1e-4, 1e-2, 0.0, 0.0, 0.0]))
    assert ekf.update_heading(-math.pi + 0.01, 0.01)
    assert abs(ekf.x[2]) > math.pi - 0.01


def test_a_snapshot_brings_back_the_counts_and_the_held_steering():
    ekf = started_ekf(KinematicBicycleModel(ProcessNoise(), 2.7))
    ekf.hold_steering(0.05)
    snap = ekf.snapshot()
    ekf.hold_steering(-0.05)
    ekf.update_speed(20.0, 0.1)
    ekf.predict_to(0.5)
    ekf.restore(snap)
    assert ekf.steering_angle_rad == 0.05 and ekf.update_counts() == {}
    assert ekf.time_s == 0.0 and ekf.x == pytest.approx(STATE)


def test_a_snapshot_from_before_the_start_leaves_the_filter_uninitialised():
    ekf = GeolocationEkf()
    snap = ekf.snapshot()
    ekf.initialise(1.0, STATE, np.eye(STATE_DIM))
    ekf.restore(snap)
    assert not ekf.initialised


@pytest.mark.parametrize(("update", "row", "bias_row", "bias"), [
    ("update_yaw_rate", YAW_RATE, YAW_RATE_BIAS, -0.003), ("update_accel", ACCEL, ACCEL_BIAS, 0.05)])
def test_an_inertial_units_constant_bias_is_learnt_while_the_wheels_tell_the_truth(update, row, bias_row, bias):
    """The inertial unit reads the truth plus its bias; the wheels read the truth. The filter splits the two."""
    ekf = GeolocationEkf()
    truth = np.array([0.0, 0.0, 0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    ekf.initialise(0.0, truth, np.diag([0.01, 0.01, 1e-4, 0.01, 1e-2, 0.1, 0.005**2, 0.1**2, 0.0, 0.0, 0.0]))
    for k in range(1, 3001):
        ekf.predict_to(k * 0.01)
        getattr(ekf, update)(bias, 0.005 if row == YAW_RATE else 0.1)
        ekf.update_odometry(20.0, 0.0, 0.01, 0.01)
    assert ekf.x[bias_row] == pytest.approx(bias, rel=0.1)
    assert abs(ekf.x[row]) < abs(bias) / 5


def _two_sigma_shares(gnss_error_std_m: float, runs: int = 8, seconds: float = 60.0) -> float:
    """A car driving straight at 20 m/s, wheels telling its speed at 10 Hz, fixes at 5 Hz whose error is a first-order
    Gauss-Markov process (0.5 m, 60 s, as the simulator's receiver) plus 0.1 m of white noise; the filter told
    gnss_error_std_m of correlated error. The share of samples whose 2-sigma ellipse holds the truth."""
    correlated_std_m, white_std_m, time_s, fix_dt_s = 0.5, 0.1, 60.0, 0.2
    decay = math.exp(-fix_dt_s / time_s)
    inside = []
    for seed in range(runs):
        rng = np.random.default_rng(seed)
        ekf = GeolocationEkf(CtraModel(ProcessNoise(gnss_error_std_m=gnss_error_std_m, gnss_error_time_s=time_s)))
        error_m = rng.normal(0.0, correlated_std_m, 2)
        error_var = gnss_error_std_m**2
        P0 = np.diag([white_std_m**2 + error_var] * 2 + [1e-4, 0.01, 1e-4, 0.1, 1e-4, 1e-2] + [error_var] * 2 + [0.0])
        P0[0, 8] = P0[8, 0] = P0[1, 9] = P0[9, 1] = -error_var
        fix = error_m + rng.normal(0.0, white_std_m, 2)
        ekf.initialise(0.0, np.array([fix[0], fix[1], 0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]), P0)
        for step in range(1, int(seconds / fix_dt_s) + 1):
            t = step * fix_dt_s
            for k in (1, 2):
                ekf.predict_to(t - fix_dt_s + k * fix_dt_s / 2)
                ekf.update_odometry(20.0 + rng.normal(0.0, 0.02), rng.normal(0.0, 0.001), 0.02, 0.001)
            error_m = decay * error_m + rng.normal(0.0, correlated_std_m * math.sqrt(1 - decay**2), 2)
            fix = np.array([20.0 * t, 0.0]) + error_m + rng.normal(0.0, white_std_m, 2)
            ekf.update_gnss_position(fix[0], fix[1], white_std_m, white_std_m, LeverArm())
            offset = ekf.x[:2] - [20.0 * t, 0.0]
            inside.append(float(offset @ np.linalg.solve(ekf.P[:2, :2], offset)) <= 4.0)
    return float(np.mean(inside))


def test_fixes_whose_error_wanders_slowly_are_not_averaged_into_false_confidence():
    """Taken as white, 300 fixes a minute convince the filter it knows the position to centimetres while the fixes'
    error wanders by half a metre: the truth falls outside its 2-sigma ellipse most of the time. With the
    correlated error in the state, the ellipse holds the truth about 1 - exp(-2) = 86.5 % of the time."""
    white_share = _two_sigma_shares(gnss_error_std_m=0.0)
    modelled_share = _two_sigma_shares(gnss_error_std_m=0.5)
    assert white_share < 0.5
    assert 0.80 <= modelled_share <= 0.93
