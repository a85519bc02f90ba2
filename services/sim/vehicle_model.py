"""Kinematic bicycle at the rear axle with lagged, delayed and limited actuators.

Inputs are what actuation's CAN command frames carry: an acceleration request and a road-wheel angle
request; a throttle/brake pedal path is mapped back to an acceleration request.
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, replace

from coopdrive.services.sim.profiles import VehicleProfile

DEFAULT_SUBSTEPS = 10


@dataclass(frozen=True)
class VehicleState:
    x_m: float = 0.0
    y_m: float = 0.0
    heading_rad: float = 0.0
    speed_mps: float = 0.0
    accel_mps2: float = 0.0
    steer_rad: float = 0.0
    yaw_rate_radps: float = 0.0
    jerk_mps3: float = 0.0
    travelled_m: float = 0.0


def lag_alpha(dt_s: float, time_constant_s: float) -> float:
    """(engine lag) alpha = dt / (tau + dt) of a_k = alpha u_k + (1 - alpha) a_{k-1}."""
    return dt_s / (time_constant_s + dt_s)


class _DeadTime:
    """A fixed delay of whole substeps, holding `initial` until the first request comes out."""

    def __init__(self, steps: int, initial: float) -> None:
        self._queue: deque[float] = deque([initial] * steps)

    def push(self, value: float) -> float:
        self._queue.append(value)
        return self._queue.popleft()


class VehicleModel:
    """Steps at a fixed dt_s with `substeps` internal Euler substeps; deterministic for the same inputs."""

    def __init__(self, profile: VehicleProfile, dt_s: float, state: VehicleState | None = None,
                 substeps: int = DEFAULT_SUBSTEPS) -> None:
        if dt_s <= 0 or substeps < 1:
            raise ValueError(f"dt_s must be > 0 and substeps >= 1, got dt_s={dt_s}, substeps={substeps}")
        self.profile = profile
        self.dt_s = dt_s
        self.substeps = substeps
        self.substep_s = dt_s / substeps
        self.state = state or VehicleState()
        self._accel_alpha = lag_alpha(self.substep_s, profile.accel_time_constant_s)
        self._steer_alpha = lag_alpha(self.substep_s, profile.steer_time_constant_s)
        self._accel_delay = _DeadTime(round(profile.accel_dead_time_s / self.substep_s), self.state.accel_mps2)
        self._steer_delay = _DeadTime(round(profile.steer_dead_time_s / self.substep_s), self.state.steer_rad)
        self.accel_request_mps2 = self.state.accel_mps2
        self.steer_request_rad = self.state.steer_rad

    def clip_accel_request(self, accel_mps2: float) -> float:
        return min(max(accel_mps2, -self.profile.max_decel_mps2), self.profile.max_accel_mps2)

    def pedals_to_accel_mps2(self, throttle_ratio: float, brake_ratio: float) -> float:
        """Pedal ratios in [0, 1] to an acceleration request; the brake wins when both are pressed."""
        throttle = min(max(throttle_ratio, 0.0), 1.0)
        brake = min(max(brake_ratio, 0.0), 1.0)
        if brake > 0.0:
            return -brake * self.profile.max_decel_mps2
        return throttle * self.profile.max_accel_mps2

    def pedals(self) -> tuple[float, float, float]:
        """(throttle_ratio, brake_ratio, brake_pressure_bar) that produce the current acceleration."""
        accel = self.state.accel_mps2
        throttle = max(accel, 0.0) / self.profile.max_accel_mps2
        brake = max(-accel, 0.0) / self.profile.max_decel_mps2
        return throttle, brake, brake * self.profile.max_brake_pressure_bar

    def step(self, accel_request_mps2: float, steer_request_rad: float) -> VehicleState:
        """Advance one dt_s with the requests held constant over it."""
        if not (math.isfinite(accel_request_mps2) and math.isfinite(steer_request_rad)):
            raise ValueError(f"non-finite request: accel {accel_request_mps2}, steer {steer_request_rad}")
        self.accel_request_mps2 = self.clip_accel_request(accel_request_mps2)
        limit = self.profile.max_steer_rad
        self.steer_request_rad = min(max(steer_request_rad, -limit), limit)
        for _ in range(self.substeps):
            self._substep()
        return self.state

    def step_pedals(self, throttle_ratio: float, brake_ratio: float, steer_request_rad: float) -> VehicleState:
        return self.step(self.pedals_to_accel_mps2(throttle_ratio, brake_ratio), steer_request_rad)

    def _substep(self) -> None:
        p, s, h = self.profile, self.state, self.substep_s
        delayed_accel = self._accel_delay.push(self.accel_request_mps2)
        accel = self._accel_alpha * delayed_accel + (1.0 - self._accel_alpha) * s.accel_mps2  # (engine lag)
        max_jerk_step = p.max_jerk_mps3 * h
        accel = min(max(accel, s.accel_mps2 - max_jerk_step), s.accel_mps2 + max_jerk_step)
        accel = min(max(accel, -p.max_decel_mps2), p.max_accel_mps2)

        delayed_steer = self._steer_delay.push(self.steer_request_rad)
        steer = self._steer_alpha * delayed_steer + (1.0 - self._steer_alpha) * s.steer_rad
        max_steer_step = p.max_steer_rate_radps * h
        steer = min(max(steer, s.steer_rad - max_steer_step), s.steer_rad + max_steer_step)
        steer = min(max(steer, -p.max_steer_rad), p.max_steer_rad)

        speed = s.speed_mps + accel * h
        if speed <= 0.0:
            # No reverse: a vehicle braking to a stop stays stopped and its acceleration vanishes.
            speed, accel = 0.0, max(accel, 0.0)
        speed = min(speed, p.max_speed_mps)
        mean_speed = 0.5 * (s.speed_mps + speed)
        yaw_rate = mean_speed * math.tan(steer) / p.wheelbase_m  # (eq. 5) kinematic bicycle
        heading = s.heading_rad + yaw_rate * h
        mid_heading = s.heading_rad + 0.5 * yaw_rate * h
        self.state = replace(
            s,
            x_m=s.x_m + mean_speed * math.cos(mid_heading) * h,
            y_m=s.y_m + mean_speed * math.sin(mid_heading) * h,
            heading_rad=math.atan2(math.sin(heading), math.cos(heading)),
            speed_mps=speed,
            accel_mps2=accel,
            steer_rad=steer,
            yaw_rate_radps=yaw_rate,
            jerk_mps3=(accel - s.accel_mps2) / h,
            travelled_m=s.travelled_m + mean_speed * h,
        )
