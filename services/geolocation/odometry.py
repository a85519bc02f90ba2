"""Speed and yaw rate from the wheel speeds on the CAN bus (DRIVERTIVE, eq. 8)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.v1 import vehicle_pb2

# Wheel speeds beyond this are sensor faults, not driving (~540 km/h).
MAX_WHEEL_SPEED_MPS = 150.0


@dataclass(frozen=True)
class OdometrySample:
    time_s: float
    speed_mps: float
    yaw_rate_radps: float
    steering_angle_rad: float
    speed_std_mps: float
    yaw_rate_std_radps: float


class Odometry:
    """Rear-wheel odometry at the rear-axle centre: v = (v_r + v_l) / 2, yaw rate = (v_r - v_l) / d."""

    def __init__(self, track_width_m: float, wheel_speed_std_mps: float) -> None:
        if track_width_m <= 0.0:
            raise ValueError(f"track_width_m must be positive, got {track_width_m}")
        self.track_width_m = track_width_m
        self.wheel_speed_std_mps = wheel_speed_std_mps
        # Independent wheel noises: var(mean) = s^2 / 2, var(difference / d) = 2 s^2 / d^2, uncorrelated.
        self.speed_std_mps = wheel_speed_std_mps / math.sqrt(2.0)
        self.yaw_rate_std_radps = math.sqrt(2.0) * wheel_speed_std_mps / track_width_m

    def sample(self, msg: vehicle_pb2.VehicleCanState) -> OdometrySample:
        """Raises ValueError naming the bad wheel when a speed is not finite or out of range."""
        left = msg.wheel_speed_rear_left_mps
        right = msg.wheel_speed_rear_right_mps
        for name, value in (("rear_left", left), ("rear_right", right)):
            if not math.isfinite(value) or abs(value) > MAX_WHEEL_SPEED_MPS:
                raise ValueError(f"wheel speed {name} = {value} m/s is not a plausible speed")
        if not math.isfinite(msg.steering_angle_rad):
            raise ValueError(f"steering angle {msg.steering_angle_rad} rad is not finite")
        sign = -1.0 if msg.gear == vehicle_pb2.GEAR_REVERSE else 1.0
        speed_mps = sign * 0.5 * (left + right)
        yaw_rate_radps = sign * (right - left) / self.track_width_m  # (eq. 8) DRIVERTIVE
        return OdometrySample(
            time_s=msg.header.sample_time_s,
            speed_mps=speed_mps,
            yaw_rate_radps=yaw_rate_radps,
            steering_angle_rad=msg.steering_angle_rad,
            speed_std_mps=self.speed_std_mps,
            yaw_rate_std_radps=self.yaw_rate_std_radps,
        )
