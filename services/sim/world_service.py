"""The follow world: a straight lane, a scripted leader and stack-driven vehicles.

A deliberately small world for the closed loop of the foundation; sensor values are what a
vehicle would measure (GNSS position with noise, wheel speeds, a radar range to the leader).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from coopdrive.services.sim.world_config import VehicleSpec, WorldConfig


@dataclass
class VehicleBody:
    """Kinematic bicycle with first-order acceleration lag and a dead time."""

    spec: VehicleSpec
    x_m: float
    y_m: float
    heading_rad: float
    speed_mps: float
    accel_mps2: float = 0.0
    steering_angle_rad: float = 0.0
    yaw_rate_radps: float = 0.0
    # Steps of delay the command already had before reaching the model (lockstep pipelining).
    already_delayed_steps: int = 0
    _delayed_requests: deque = field(default_factory=deque)

    def step(self, dt_s: float, accel_request_mps2: float, steering_request_rad: float) -> None:
        spec = self.spec
        self._delayed_requests.append(accel_request_mps2)
        delay_steps = max(1, round(spec.dead_time_s / dt_s) - self.already_delayed_steps)
        while len(self._delayed_requests) > delay_steps:
            self._delayed_requests.popleft()
        applied = self._delayed_requests[0]
        applied = min(max(applied, -spec.max_decel_mps2), spec.max_accel_mps2)
        alpha = dt_s / (spec.accel_lag_s + dt_s)  # a_k = alpha u_k + (1 - alpha) a_(k-1)
        self.accel_mps2 = alpha * applied + (1 - alpha) * self.accel_mps2
        if self.speed_mps <= 0 and self.accel_mps2 < 0:
            self.accel_mps2 = 0.0
        self.steering_angle_rad = min(max(steering_request_rad, -spec.max_steering_rad), spec.max_steering_rad)
        self.speed_mps = max(0.0, self.speed_mps + self.accel_mps2 * dt_s)
        self.yaw_rate_radps = self.speed_mps * math.tan(self.steering_angle_rad) / spec.wheelbase_m
        self.heading_rad += self.yaw_rate_radps * dt_s
        self.x_m += self.speed_mps * math.cos(self.heading_rad) * dt_s
        self.y_m += self.speed_mps * math.sin(self.heading_rad) * dt_s

    @property
    def front_bumper_x_m(self) -> float:
        return self.x_m + (self.spec.length_m - self.spec.rear_overhang_m) * math.cos(self.heading_rad)

    @property
    def rear_bumper_x_m(self) -> float:
        return self.x_m - self.spec.rear_overhang_m * math.cos(self.heading_rad)


class SpeedProfile:
    """Piecewise-linear speed over time, from [[time_s, speed_mps], ...]."""

    def __init__(self, points: list[tuple[float, float]]):
        self._times = np.array([p[0] for p in points], dtype=float)
        self._speeds = np.array([p[1] for p in points], dtype=float)

    def speed_at(self, time_s: float) -> float:
        return float(np.interp(time_s, self._times, self._speeds))


class FollowWorld:
    def __init__(self, config: WorldConfig, step_s: float, already_delayed_steps: int = 0):
        """`already_delayed_steps`: at most this many steps of lockstep delay are taken off the stack vehicles'
        dead times; fewer when a dead time is shorter (see pipelined_steps)."""
        self.config = config
        self.bodies: dict[str, VehicleBody] = {}
        self.profiles: dict[str, SpeedProfile] = {}
        stack_specs = [spec for spec in config.vehicles if not spec.speed_profile]
        # One step of the dead time always stays in the model (VehicleBody keeps at least one step).
        absorbable = min((round(spec.dead_time_s / step_s) - 1 for spec in stack_specs), default=already_delayed_steps)
        self.pipelined_steps = max(0, min(already_delayed_steps, absorbable))
        for spec in config.vehicles:
            # Scripted vehicles follow their profile directly: lockstep never delays their requests.
            delayed = 0 if spec.speed_profile else self.pipelined_steps
            self.bodies[spec.vehicle_id] = VehicleBody(spec, spec.station_m, spec.lateral_m, 0.0, spec.speed_mps,
                                                       already_delayed_steps=delayed)
            if spec.speed_profile:
                self.profiles[spec.vehicle_id] = SpeedProfile(spec.speed_profile)

    def step(self, time_s: float, dt_s: float, accel_requests: dict[str, float], steering_requests: dict[str, float]) -> None:
        for vehicle_id, body in self.bodies.items():
            if vehicle_id in self.profiles:
                target = self.profiles[vehicle_id].speed_at(time_s + dt_s)
                request = (target - body.speed_mps) / max(body.spec.accel_lag_s, dt_s)
                body.step(dt_s, request, 0.0)
            else:
                body.step(dt_s, accel_requests.get(vehicle_id, 0.0), steering_requests.get(vehicle_id, 0.0))

    def vehicle_ahead(self, vehicle_id: str) -> VehicleBody | None:
        me = self.bodies[vehicle_id]
        ahead = [b for i, b in self.bodies.items() if i != vehicle_id and b.x_m > me.x_m
                 and abs(b.y_m - me.y_m) < self.config.lane_width_m / 2]
        return min(ahead, key=lambda b: b.x_m, default=None)

    def gap_m(self, vehicle_id: str) -> float | None:
        """Bumper-to-bumper distance to the vehicle ahead in the lane."""
        ahead = self.vehicle_ahead(vehicle_id)
        return None if ahead is None else ahead.rear_bumper_x_m - self.bodies[vehicle_id].front_bumper_x_m
