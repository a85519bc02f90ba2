import math

import pytest

from coopdrive.services.actuation.config import SteeringConfig
from coopdrive.services.actuation.steering_map import SteeringMap


def test_a_curvature_becomes_the_kinematic_bicycle_angle():
    steering = SteeringMap(SteeringConfig(wheelbase_m=2.5, use_curvature=True))
    assert steering.target_angle_rad(0.0, 0.02) == pytest.approx(math.atan(2.5 * 0.02))


def test_the_angle_request_is_used_unless_curvature_is_configured():
    assert SteeringMap(SteeringConfig()).target_angle_rad(0.1, 0.02) == 0.1


def test_the_angle_never_exceeds_the_actuator_range_at_low_speed():
    config = SteeringConfig(max_road_wheel_angle_rad=0.5, max_angle_rate_radps=100.0)
    request = SteeringMap(config).map(0.9, 0.0, speed_mps=0.5, dt_s=0.1)
    assert request.angle_rad == 0.5 and request.limited


def test_the_angle_range_shrinks_with_speed_to_bound_lateral_acceleration():
    config = SteeringConfig(max_lateral_accel_mps2=3.0, max_angle_rate_radps=100.0)
    steering = SteeringMap(config)
    speed_mps = 25.0
    angle = steering.map(0.5, 0.0, speed_mps=speed_mps, dt_s=0.1).angle_rad
    lateral_accel_mps2 = speed_mps**2 * math.tan(angle) / config.wheelbase_m
    assert lateral_accel_mps2 == pytest.approx(3.0)


def test_the_angle_moves_no_faster_than_the_rate_limit():
    steering = SteeringMap(SteeringConfig(max_angle_rate_radps=0.4))
    request = steering.map(-0.3, 0.1, speed_mps=5.0, dt_s=0.05)
    assert request.angle_rad == pytest.approx(0.1 - 0.02)
