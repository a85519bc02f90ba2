import math

import pytest

from coopdrive.services.geolocation.odometry import Odometry
from coopdrive.v1 import vehicle_pb2


def can(left_mps: float, right_mps: float, gear=vehicle_pb2.GEAR_DRIVE) -> vehicle_pb2.VehicleCanState:
    msg = vehicle_pb2.VehicleCanState(wheel_speed_rear_left_mps=left_mps, wheel_speed_rear_right_mps=right_mps,
                                      steering_angle_rad=0.05, gear=gear)
    msg.header.sample_time_s = 3.0
    return msg


def test_speed_is_the_mean_and_yaw_rate_the_difference_of_the_rear_wheels_over_the_track():
    sample = Odometry(track_width_m=1.6, wheel_speed_std_mps=0.01).sample(can(9.8, 10.2))
    assert sample.speed_mps == pytest.approx(10.0)
    assert sample.yaw_rate_radps == pytest.approx(0.4 / 1.6)  # (eq. 8): turning left, right wheel faster
    assert (sample.time_s, sample.steering_angle_rad) == (3.0, 0.05)


def test_in_reverse_the_speed_and_yaw_rate_change_sign():
    sample = Odometry(1.6, 0.01).sample(can(2.2, 1.8, gear=vehicle_pb2.GEAR_REVERSE))
    assert (sample.speed_mps, sample.yaw_rate_radps) == pytest.approx((-2.0, 0.25))


def test_the_noise_of_speed_and_yaw_rate_follows_from_the_wheel_noise():
    odometry = Odometry(track_width_m=2.0, wheel_speed_std_mps=0.1)
    assert odometry.speed_std_mps == pytest.approx(0.1 / math.sqrt(2.0))
    assert odometry.yaw_rate_std_radps == pytest.approx(0.1 * math.sqrt(2.0) / 2.0)


@pytest.mark.parametrize("bad", [math.nan, math.inf, 500.0])
def test_an_implausible_wheel_speed_raises_naming_the_wheel(bad):
    with pytest.raises(ValueError, match="rear_right"):
        Odometry(1.6, 0.01).sample(can(10.0, bad))


def test_a_non_positive_track_width_is_refused():
    with pytest.raises(ValueError, match="track_width_m"):
        Odometry(0.0, 0.01)
