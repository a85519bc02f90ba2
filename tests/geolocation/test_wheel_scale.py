"""The wheel-radius scale: a scalar Kalman filter on true speed / reported wheel speed, fed by GNSS speed over
ground; what the odometry then reports is the wheels' speed times that scale."""

import numpy as np
import pytest
from geolocation_drive import ORIGIN, can_state, drive, gnss_fix

from coopdrive.can.adapter import OdometryOptions
from coopdrive.services.geolocation.config import GeolocatorConfig
from coopdrive.services.geolocation.geolocator import Geolocator
from coopdrive.services.geolocation.odometry import Odometry
from coopdrive.services.geolocation.wheel_scale import GNSS_SPEED_STD_MPS, WheelScaleEstimator
from coopdrive.v1 import vehicle_pb2

# Worn tyres roll on a smaller radius than the ECU assumes: the wheels over-report the speed by 2 %.
TRUE_SCALE = 1.0 / 1.02
WHEEL_PERIOD_S = 0.01
FIX_PERIOD_S = 0.1


def accelerate(estimator: WheelScaleEstimator, duration_s: float, rng: np.random.Generator, outlier_at_s=None) -> None:
    """Accelerating from 5 to 25 m/s; wheels at 100 Hz, GNSS at 10 Hz with its speed noise."""
    for k in range(round(duration_s / WHEEL_PERIOD_S)):
        time_s = k * WHEEL_PERIOD_S
        true_speed_mps = 5.0 + 20.0 * time_s / duration_s
        estimator.on_wheel_speed(time_s, true_speed_mps / TRUE_SCALE)
        if k % round(FIX_PERIOD_S / WHEEL_PERIOD_S) == 0:
            gnss_speed_mps = true_speed_mps + rng.normal(0.0, GNSS_SPEED_STD_MPS)
            if outlier_at_s is not None and abs(time_s - outlier_at_s) < 1e-9:
                gnss_speed_mps += 5.0
            estimator.on_gnss_speed(time_s, gnss_speed_mps)


def test_a_minute_of_gnss_speed_finds_the_wheel_scale_within_a_thousandth():
    estimator = WheelScaleEstimator()
    accelerate(estimator, 60.0, np.random.default_rng(7))
    assert estimator.scale == pytest.approx(TRUE_SCALE, abs=1e-3)
    assert estimator.std < 1e-3
    assert estimator.counts["wheel_scale_updates"] > 500


def test_a_fix_far_off_the_wheels_is_gated_out_and_does_not_pull_the_scale():
    estimator = WheelScaleEstimator()
    accelerate(estimator, 60.0, np.random.default_rng(7), outlier_at_s=30.0)
    assert estimator.counts["wheel_scale_gated"] == 1
    assert estimator.scale == pytest.approx(TRUE_SCALE, abs=1e-3)


def test_below_walking_pace_or_without_wheel_speeds_either_side_of_the_fix_nothing_is_learnt():
    estimator = WheelScaleEstimator()
    estimator.on_gnss_speed(1.0, 10.0)  # waits for a wheel sample after 1.0 s
    estimator.on_wheel_speed(2.0, 1.0)  # none before it: the fix is not used
    estimator.on_gnss_speed(2.0, 1.0)  # walking pace
    estimator.on_wheel_speed(2.5, 20.0)
    estimator.on_gnss_speed(2.2, 20.0)  # the samples either side are 0.5 s apart
    assert estimator.scale == 1.0 and estimator.counts["wheel_scale_unused"] == 3


def test_a_fix_that_arrives_before_the_wheels_report_its_time_is_paired_when_they_do():
    """The wheel frames reach the service 65 ms after the fix showing the same moment (their latency): each fix is
    paired with the wheels' speed at its own time, interpolated, once the sample after it has come."""
    estimator = WheelScaleEstimator()
    latency_s = 0.065
    for k in range(3000):
        now_s = k * WHEEL_PERIOD_S
        true_speed_mps = 5.0 + 20.0 * now_s / 30.0  # 0.67 m/s2: at 65 ms off, the scale would be 0.2-0.9 % off
        wheel_time_s = now_s - latency_s
        estimator.on_wheel_speed(wheel_time_s, (5.0 + 20.0 * wheel_time_s / 30.0) / TRUE_SCALE)
        if k % 10 == 5:
            estimator.on_gnss_speed(now_s, true_speed_mps)
    assert estimator.counts["wheel_scale_updates"] > 290 and estimator.counts["wheel_scale_unused"] == 0
    assert estimator.scale == pytest.approx(TRUE_SCALE, abs=2e-4)


def test_the_odometry_reports_the_four_wheels_times_the_learnt_scale():
    odometry = Odometry(1.6, 0.05, OdometryOptions(speed_wheels="all", yaw_rate_from_wheels=False,
                                                    estimate_wheel_scale=True))
    rng = np.random.default_rng(3)
    for k in range(3000):
        time_s = k * WHEEL_PERIOD_S
        wheel_mps = 20.0 / TRUE_SCALE
        state = vehicle_pb2.VehicleCanState(wheel_speed_front_left_mps=wheel_mps, wheel_speed_front_right_mps=wheel_mps,
                                            wheel_speed_rear_left_mps=wheel_mps, wheel_speed_rear_right_mps=wheel_mps)
        state.header.sample_time_s = time_s
        sample = odometry.sample(state)
        if k % 10 == 0:
            odometry.on_gnss_speed(time_s, 20.0 + rng.normal(0.0, GNSS_SPEED_STD_MPS))
    assert sample.speed_mps == pytest.approx(20.0, abs=0.03)
    assert sample.yaw_rate_radps is None
    assert odometry.stats()["wheel_scale_updates"] > 250


def test_geolocation_learns_the_scale_from_the_fixes_it_receives_and_reports_the_true_speed():
    geolocator = Geolocator(GeolocatorConfig(antenna_x_m=1.0), origin=ORIGIN)
    geolocator.configure_odometry(OdometryOptions(estimate_wheel_scale=True))
    truth = drive(40.0, 20.0, None, 500.0)
    rng = np.random.default_rng(5)
    for i in range(len(truth.time_s)):
        state = can_state(truth, i, rng, 0.01)
        state.wheel_speed_rear_left_mps /= TRUE_SCALE
        state.wheel_speed_rear_right_mps /= TRUE_SCALE
        geolocator.on_can_state(state)
        if i % 10 == 0:
            fix, _, _ = gnss_fix(truth, i, rng, 0.05, 1.0)
            fix.speed_mps += rng.normal(0.0, GNSS_SPEED_STD_MPS)
            geolocator.on_gnss_fix(fix)
    assert geolocator.odometry.scale == pytest.approx(TRUE_SCALE, abs=2e-3)
    assert geolocator.estimate(truth.time_s[-1]).speed_mps == pytest.approx(20.0, abs=0.05)
    assert geolocator.stats()["wheel_scale_updates"] > 300
