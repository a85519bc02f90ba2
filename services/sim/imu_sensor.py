"""An inertial unit at the rear axle: longitudinal and lateral acceleration and yaw rate, with noise and bias."""
from __future__ import annotations

import numpy as np

from coopdrive.services.sim.sensor_config import ImuConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.v1 import sim_pb2, vehicle_pb2


class ImuSensor(TimedSensor[vehicle_pb2.ImuSample]):
    def __init__(self, config: ImuConfig, rng: np.random.Generator, vehicle_id: str) -> None:
        self.config = config
        super().__init__(config.timing, rng, vehicle_id)
        # This unit's biases: the configured ones plus a turn-on bias drawn once (not at all when zero, so that an
        # ideal unit's noise sequence is unchanged).
        self.accel_bias_mps2 = config.accel_bias_mps2 + self._turn_on_bias(config.accel_turn_on_bias_sigma_mps2)
        self.yaw_rate_bias_radps = config.yaw_rate_bias_radps + self._turn_on_bias(
            config.yaw_rate_turn_on_bias_sigma_radps)

    def _turn_on_bias(self, sigma: float) -> float:
        return sigma * float(self.rng.standard_normal()) if sigma > 0.0 else 0.0

    def poll(self, now_s: float, ego: sim_pb2.VehicleTruth) -> list[vehicle_pb2.ImuSample]:
        return self._deliver(now_s, lambda: self._measure(ego))

    def _measure(self, ego: sim_pb2.VehicleTruth) -> vehicle_pb2.ImuSample:
        cfg = self.config
        noise = self.rng.standard_normal(3)
        # At the rear axle of a kinematic bicycle the lateral acceleration is centripetal only: v * yaw rate.
        return vehicle_pb2.ImuSample(
            accel_longitudinal_mps2=ego.accel_mps2 + self.accel_bias_mps2 + cfg.accel_sigma_mps2 * noise[0],
            accel_lateral_mps2=ego.speed_mps * ego.yaw_rate_radps + cfg.accel_sigma_mps2 * noise[1],
            yaw_rate_radps=ego.yaw_rate_radps + self.yaw_rate_bias_radps + cfg.yaw_rate_sigma_radps * noise[2],
        )
