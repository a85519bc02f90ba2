"""Kinematic bicycle at the rear axle with lagged, delayed and limited actuators.

Inputs are what actuation's CAN command frames carry: an acceleration (or deceleration) request, or throttle
and brake ratios mapped back to one, and a road-wheel angle request.
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

from coopdrive.services.sim.profiles import STANDARD_GRAVITY_MPS2, VehicleProfile

DEFAULT_SUBSTEPS = 10


@dataclass(frozen=True)
class VehicleState:
    x_m: float = 0.0
    y_m: float = 0.0
    heading_rad: float = 0.0
    speed_mps: float = 0.0
    # Actual longitudinal acceleration (actuator output minus driving resistance).
    accel_mps2: float = 0.0
    # Road-wheel angle, positive to the left.
    steer_rad: float = 0.0
    yaw_rate_radps: float = 0.0
    jerk_mps3: float = 0.0
    travelled_m: float = 0.0


def lag_alpha(dt_s: float, time_constant_s: float) -> float:
    """(engine lag) alpha = dt / (tau + dt) of a_k = alpha u_k + (1 - alpha) a_{k-1}."""
    return dt_s / (time_constant_s + dt_s)


def driving_resistance_mps2(profile: VehicleProfile, grade_mps2: float, speed_mps: float) -> float:
    """Rolling and aerodynamic resistance while moving, plus the grade's share of gravity (grade_mps2)."""
    if speed_mps <= 0.0:
        return grade_mps2
    return profile.rolling_resistance_mps2 + profile.drag_1pm * speed_mps * speed_mps + grade_mps2


def _clip(value: float, low: float, high: float) -> float:
    return min(max(value, low), high)


class _DeadTime:
    """A fixed delay of whole substeps, holding `initial` until the first request comes out: each substep appends
    the request to `queue` and takes the oldest out."""

    def __init__(self, steps: int, initial: float) -> None:
        self.queue: deque[float] = deque([initial] * steps)


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
        # Road grade, positive uphill (the maps are flat: 0 unless a caller sets it).
        self.grade_rad = 0.0
        self._accel_alpha = lag_alpha(self.substep_s, profile.response_time_constant_s)
        self._steer_alpha = lag_alpha(self.substep_s, profile.steer_time_constant_s)
        # The actuator starts where it holds the initial acceleration against the driving resistance.
        self.actuator_accel_mps2 = self.state.accel_mps2 + self.resistance_mps2(self.state.speed_mps)
        self._accel_delay = _DeadTime(round(profile.response_dead_time_s / self.substep_s), self.actuator_accel_mps2)
        self._steer_delay = _DeadTime(round(profile.steer_dead_time_s / self.substep_s), self.state.steer_rad)
        self.accel_request_mps2 = self.actuator_accel_mps2
        self.steer_request_rad = self.state.steer_rad

    def resistance_mps2(self, speed_mps: float) -> float:
        return driving_resistance_mps2(self.profile, STANDARD_GRAVITY_MPS2 * math.sin(self.grade_rad), speed_mps)

    def clip_accel_request(self, accel_mps2: float) -> float:
        return _clip(accel_mps2, -self.profile.max_decel_mps2, self.profile.max_accel_mps2)

    def command_to_accel_mps2(self, throttle_ratio: float, brake_ratio: float,
                              deceleration_request_mps2: float = 0.0) -> float:
        """ACT_LongitudinalCommand to an acceleration request: a brake-by-wire deceleration request wins,
        then the brake ratio, then the throttle ratio (each scaled by the profile's full-pedal values)."""
        if deceleration_request_mps2 > 0.0:
            return -deceleration_request_mps2
        brake = _clip(brake_ratio, 0.0, 1.0)
        if brake > 0.0:
            return -brake * self.profile.max_decel_mps2
        return _clip(throttle_ratio, 0.0, 1.0) * self.profile.max_accel_mps2

    def brake_pressure_bar(self) -> float:
        """Brake line pressure for the braking the actuator applies now."""
        braking_share = max(-self.actuator_accel_mps2, 0.0) / self.profile.max_decel_mps2
        return braking_share * self.profile.max_brake_pressure_bar

    def step(self, accel_request_mps2: float, steer_request_rad: float) -> VehicleState:
        """Advance one dt_s with the requests held constant over it."""
        if not (math.isfinite(accel_request_mps2) and math.isfinite(steer_request_rad)):
            raise ValueError(f"non-finite request: accel {accel_request_mps2}, steer {steer_request_rad}")
        self.accel_request_mps2 = self.clip_accel_request(accel_request_mps2)
        limit = self.profile.max_steer_rad
        self.steer_request_rad = _clip(steer_request_rad, -limit, limit)
        self._substeps()
        return self.state

    def step_command(self, throttle_ratio: float, brake_ratio: float, deceleration_request_mps2: float,
                     steer_request_rad: float) -> VehicleState:
        """Advance one dt_s with the values of the ACT_ command frames."""
        accel = self.command_to_accel_mps2(throttle_ratio, brake_ratio, deceleration_request_mps2)
        return self.step(accel, steer_request_rad)

    def _substeps(self) -> None:
        """The step's Euler substeps. The state lives in local floats between them (a VehicleState and a few calls
        per substep were most of the model's time); every operation and its order are the same as one substep at
        a time, so the numbers are too."""
        p, h, s = self.profile, self.substep_s, self.state
        accel_alpha, steer_alpha = self._accel_alpha, self._steer_alpha
        accel_queue, steer_queue = self._accel_delay.queue, self._steer_delay.queue
        accel_request, steer_request = self.accel_request_mps2, self.steer_request_rad
        max_jerk_h, max_steer_rate_h = p.max_jerk_mps3 * h, p.max_steer_rate_radps * h
        grade_mps2 = STANDARD_GRAVITY_MPS2 * math.sin(self.grade_rad)
        actuator = self.actuator_accel_mps2
        x, y, heading, speed, accel = s.x_m, s.y_m, s.heading_rad, s.speed_mps, s.accel_mps2
        steer, yaw_rate, jerk, travelled = s.steer_rad, s.yaw_rate_radps, s.jerk_mps3, s.travelled_m
        for _ in range(self.substeps):
            previous_accel = accel
            # Actuator: dead time, then (engine lag), then the jerk and range limits.
            accel_queue.append(accel_request)
            lagged = accel_alpha * accel_queue.popleft() + (1.0 - accel_alpha) * actuator
            lagged = min(max(lagged, actuator - max_jerk_h), actuator + max_jerk_h)
            actuator = min(max(lagged, -p.max_decel_mps2), p.max_accel_mps2)
            accel = actuator - driving_resistance_mps2(p, grade_mps2, speed)
            steer_queue.append(steer_request)
            lagged_steer = steer_alpha * steer_queue.popleft() + (1.0 - steer_alpha) * steer
            lagged_steer = min(max(lagged_steer, steer - max_steer_rate_h), steer + max_steer_rate_h)
            steer = min(max(lagged_steer, -p.max_steer_rad), p.max_steer_rad)
            new_speed = speed + accel * h
            if new_speed <= 0.0:
                # No reverse: a vehicle braking to a stop stays stopped and its acceleration vanishes.
                new_speed, accel = 0.0, max(accel, 0.0)
            new_speed = min(new_speed, p.max_speed_mps)
            mean_speed = 0.5 * (speed + new_speed)
            yaw_rate = mean_speed * math.tan(steer) / p.wheelbase_m  # (eq. 5) kinematic bicycle
            turned = heading + yaw_rate * h
            mid_heading = heading + 0.5 * yaw_rate * h
            x += mean_speed * math.cos(mid_heading) * h
            y += mean_speed * math.sin(mid_heading) * h
            heading = math.atan2(math.sin(turned), math.cos(turned))
            speed = new_speed
            jerk = (accel - previous_accel) / h
            travelled += mean_speed * h
        self.actuator_accel_mps2 = actuator
        self.state = VehicleState(x_m=x, y_m=y, heading_rad=heading, speed_mps=speed, accel_mps2=accel,
                                  steer_rad=steer, yaw_rate_radps=yaw_rate, jerk_mps3=jerk, travelled_m=travelled)
