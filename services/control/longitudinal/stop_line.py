"""Stopping at a line: follow the speed that still allows a comfortable stop at the line.

With d the distance left to the stopping point and b_plan the planned deceleration,
    b = max(b_plan, v^2 / (2 d))                  (eq. SL3, the curve through the car where it is above the plan)
    v_allowed = sqrt(2 b d)                       (eq. SL1, constant-deceleration braking curve)
    a = -b + k (v_allowed - v)                    (eq. SL2, feed-forward of the curve plus speed feedback)
On the curve the feed-forward alone brakes at b; the feedback pulls an early car onto it, lets a car held short of
the line creep up to it, and holds a car at the line on the brake (v_allowed = 0 there). A car already above the
planned curve when the line appears (a traffic light turning amber 40-55 m ahead at 50 km/h, which the planner
stops for when 3 m/s2 suffice) brakes on the curve through its own state (SL3), at the constant deceleration that
stops it at the line: SL2 alone asked -7 m/s2 there, and the emergency path then braked at up to 3.8 m/s2.
"""

from __future__ import annotations

import math

# Planned deceleration of the braking curve: well inside the comfort limit, so the lag has room.
STOP_DECEL_MPS2 = 1.0
SPEED_GAIN_PER_S = 1.5


class StopLineApproach:
    def __init__(self, decel_mps2: float = STOP_DECEL_MPS2, speed_gain_per_s: float = SPEED_GAIN_PER_S) -> None:
        self.decel_mps2 = decel_mps2
        self.speed_gain_per_s = speed_gain_per_s

    def step(self, distance_m: float, ego_speed_mps: float) -> float:
        """Acceleration request (m/s2) for a stopping point distance_m ahead."""
        decel_mps2 = self.decel_mps2
        if distance_m > 0.0:
            decel_mps2 = max(decel_mps2, ego_speed_mps ** 2 / (2.0 * distance_m))  # (eq. SL3)
        allowed_mps = math.sqrt(2.0 * decel_mps2 * max(distance_m, 0.0))  # (eq. SL1)
        return -decel_mps2 + self.speed_gain_per_s * (allowed_mps - ego_speed_mps)  # (eq. SL2)
