"""The ego vehicle's CAN state (wheel speeds, yaw rate, steering, pedals) as VehicleCanState values."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coopdrive.services.sim.profiles import VehicleProfile
from coopdrive.services.sim.sensor_config import CanStateConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.v1 import sim_pb2, vehicle_pb2


@dataclass(frozen=True)
class DriverPedals:
    """The safety driver's own pedal positions (VEH_Pedals carries these, not the automation's requests,
    so that actuation can detect an override); zero while the driver keeps off the pedals."""

    throttle_ratio: float = 0.0
    brake_ratio: float = 0.0


def wheel_speeds_mps(speed_mps: float, yaw_rate_radps: float, wheelbase_m: float,
                     track_width_m: float) -> tuple[float, float, float, float]:
    """(front left, front right, rear left, rear right) wheel speeds of a rigid body moving at speed_mps at
    the rear axle centre and turning at yaw_rate_radps: |v + w x r| at each wheel contact point."""
    half_track = track_width_m / 2.0
    lateral_front = yaw_rate_radps * wheelbase_m

    def at(y_m: float, lateral_mps: float) -> float:
        return math.hypot(speed_mps - yaw_rate_radps * y_m, lateral_mps)

    return at(half_track, lateral_front), at(-half_track, lateral_front), at(half_track, 0.0), at(-half_track, 0.0)


class CanStateSensor(TimedSensor[vehicle_pb2.VehicleCanState]):
    def __init__(self, config: CanStateConfig, rng: np.random.Generator, profile: VehicleProfile,
                 vehicle_id: str) -> None:
        self.config = config
        self.profile = profile
        super().__init__(config.timing, rng, vehicle_id)

    def poll(self, now_s: float, ego: sim_pb2.VehicleTruth, brake_pressure_bar: float,
             driver: DriverPedals = DriverPedals()) -> list[vehicle_pb2.VehicleCanState]:
        """ego carries speed, yaw rate and road-wheel angle; brake_pressure_bar comes from
        VehicleModel.brake_pressure_bar()."""
        return self._deliver(now_s, lambda: self._measure(ego, brake_pressure_bar, driver))

    def _measure(self, ego: sim_pb2.VehicleTruth, brake_pressure_bar: float,
                 driver: DriverPedals) -> vehicle_pb2.VehicleCanState:
        cfg = self.config
        wheels = np.array(wheel_speeds_mps(ego.speed_mps, ego.yaw_rate_radps, self.profile.wheelbase_m,
                                           self.profile.track_width_m))
        wheels = np.maximum(wheels + cfg.wheel_speed_sigma_mps * self.rng.standard_normal(4), 0.0)
        return vehicle_pb2.VehicleCanState(
            wheel_speed_front_left_mps=wheels[0], wheel_speed_front_right_mps=wheels[1],
            wheel_speed_rear_left_mps=wheels[2], wheel_speed_rear_right_mps=wheels[3],
            yaw_rate_radps=ego.yaw_rate_radps + cfg.yaw_rate_sigma_radps * self.rng.standard_normal(),
            steering_angle_rad=ego.steering_angle_rad + cfg.steering_sigma_rad * self.rng.standard_normal(),
            throttle_pedal_ratio=driver.throttle_ratio,
            brake_pedal_ratio=driver.brake_ratio,
            brake_pressure_bar=brake_pressure_bar,
            gear=vehicle_pb2.GEAR_DRIVE,
        )
