"""Speed and yaw rate from the wheel speeds on the CAN bus (DRIVERTIVE, eq. 8).

How a car's wheels are read (rear pair or all four, yaw rate from the rear pair or not, the wheel-radius scale
estimated or not) comes from its vehicle CAN adapter's `odometry` options.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.can.adapter import OdometryOptions
from coopdrive.services.geolocation.wheel_scale import WheelScaleEstimator
from coopdrive.v1 import vehicle_pb2

# Wheel speeds beyond this are sensor faults, not driving (~540 km/h).
MAX_WHEEL_SPEED_MPS = 150.0


@dataclass(frozen=True)
class OdometrySample:
    time_s: float
    speed_mps: float
    # None when the car's yaw-rate sensor is trusted instead of the wheels (OdometryOptions).
    yaw_rate_radps: float | None
    steering_angle_rad: float
    speed_std_mps: float
    yaw_rate_std_radps: float


class Odometry:
    """Odometry at the rear-axle centre: v = (v_r + v_l) / 2, yaw rate = (v_r - v_l) / d.

    With speed_wheels "all", the front wheels count too, brought to the rear axle by cos(steering angle)
    (in a turn they roll on a wider circle). Speeds are times the wheel-radius scale.
    """

    def __init__(self, track_width_m: float, wheel_speed_std_mps: float,
                 options: OdometryOptions = OdometryOptions()) -> None:
        if track_width_m <= 0.0:
            raise ValueError(f"track_width_m must be positive, got {track_width_m}")
        self.track_width_m = track_width_m
        if options.wheel_speed_std_mps is not None:
            wheel_speed_std_mps = options.wheel_speed_std_mps
        self.wheel_speed_std_mps = wheel_speed_std_mps
        self.options = options
        wheels = 4 if options.speed_wheels == "all" else 2
        # Independent wheel noises: var(mean) = s^2 / n, var(difference / d) = 2 s^2 / d^2, uncorrelated.
        self.speed_std_mps = wheel_speed_std_mps / math.sqrt(wheels)
        self.yaw_rate_std_radps = math.sqrt(2.0) * wheel_speed_std_mps / track_width_m
        self.wheel_scale = WheelScaleEstimator() if options.estimate_wheel_scale else None

    @property
    def scale(self) -> float:
        return 1.0 if self.wheel_scale is None else self.wheel_scale.scale

    def sample(self, msg: vehicle_pb2.VehicleCanState) -> OdometrySample:
        """Raises ValueError naming the bad wheel when a speed is not finite or out of range."""
        wheels = {"rear_left": msg.wheel_speed_rear_left_mps, "rear_right": msg.wheel_speed_rear_right_mps}
        if self.options.speed_wheels == "all":
            wheels.update(front_left=msg.wheel_speed_front_left_mps, front_right=msg.wheel_speed_front_right_mps)
        for name, value in wheels.items():
            if not math.isfinite(value) or abs(value) > MAX_WHEEL_SPEED_MPS:
                raise ValueError(f"wheel speed {name} = {value} m/s is not a plausible speed")
        if not math.isfinite(msg.steering_angle_rad):
            raise ValueError(f"steering angle {msg.steering_angle_rad} rad is not finite")
        sign = -1.0 if msg.gear == vehicle_pb2.GEAR_REVERSE else 1.0
        left, right = wheels["rear_left"], wheels["rear_right"]
        reported_mps = 0.5 * (left + right)
        if self.options.speed_wheels == "all":
            front_mps = 0.5 * (wheels["front_left"] + wheels["front_right"]) * math.cos(msg.steering_angle_rad)
            reported_mps = 0.5 * (reported_mps + front_mps)
        if self.wheel_scale is not None:
            self.wheel_scale.on_wheel_speed(msg.header.sample_time_s, sign * reported_mps)
        yaw_rate_radps = None
        if self.options.yaw_rate_from_wheels:
            yaw_rate_radps = sign * self.scale * (right - left) / self.track_width_m  # (eq. 8) DRIVERTIVE
        return OdometrySample(
            time_s=msg.header.sample_time_s,
            speed_mps=sign * self.scale * reported_mps,
            yaw_rate_radps=yaw_rate_radps,
            steering_angle_rad=msg.steering_angle_rad,
            speed_std_mps=self.speed_std_mps,
            yaw_rate_std_radps=self.yaw_rate_std_radps,
        )

    def on_gnss_speed(self, time_s: float, speed_mps: float) -> None:
        """A fix's speed over ground: refines the wheel-radius scale when it is estimated."""
        if self.wheel_scale is not None:
            self.wheel_scale.on_gnss_speed(time_s, speed_mps)

    def stats(self) -> dict[str, int]:
        return {} if self.wheel_scale is None else dict(self.wheel_scale.counts)
