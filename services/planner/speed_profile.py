"""Arrival at a point at a given time and speed: a quintic position profile, smooth to the jerk."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class QuinticArrival:
    """s(t) from s=0, v0, a0 to s=distance_m at duration_s with speed arrival_speed_mps and no acceleration.

    Quintic so that position, speed and acceleration are continuous at both ends (no step in the
    acceleration command when the profile starts or ends).
    """

    coefficients: tuple[float, ...]
    duration_s: float
    arrival_speed_mps: float

    @classmethod
    def plan(cls, distance_m: float, duration_s: float, speed_mps: float, accel_mps2: float,
             arrival_speed_mps: float) -> QuinticArrival | None:
        """None when there is no time or no distance left: then just hold the arrival speed."""
        if duration_s <= 0 or distance_m <= 0:
            return None
        t = duration_s
        c0, c1, c2 = 0.0, speed_mps, accel_mps2 / 2.0
        lhs = np.array([[t**3, t**4, t**5], [3 * t**2, 4 * t**3, 5 * t**4], [6 * t, 12 * t**2, 20 * t**3]])
        rhs = np.array([distance_m - c1 * t - c2 * t**2, arrival_speed_mps - c1 - 2 * c2 * t, -2 * c2])
        c3, c4, c5 = np.linalg.solve(lhs, rhs)
        return cls((c0, c1, c2, float(c3), float(c4), float(c5)), duration_s, arrival_speed_mps)

    def position_m(self, t_s: float) -> float:
        t = min(max(t_s, 0.0), self.duration_s)
        return sum(c * t**i for i, c in enumerate(self.coefficients))

    def speed_mps(self, t_s: float) -> float:
        if t_s >= self.duration_s:
            return self.arrival_speed_mps
        t = max(t_s, 0.0)
        return sum(i * c * t ** (i - 1) for i, c in enumerate(self.coefficients) if i > 0)

    def accel_mps2(self, t_s: float) -> float:
        if t_s >= self.duration_s:
            return 0.0
        t = max(t_s, 0.0)
        return sum(i * (i - 1) * c * t ** (i - 2) for i, c in enumerate(self.coefficients) if i > 1)
