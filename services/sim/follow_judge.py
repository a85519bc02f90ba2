"""Judges a follow run from ground truth: collisions, gaps, speed and spacing errors."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from coopdrive.services.sim.metrics import KMH_PER_MPS, error_stats

MIN_SPEED_FOR_TIME_GAP_MPS = 1.0


@dataclass
class FollowJudge:
    standstill_m: float
    time_gap_s: float
    # Spacing is judged once the start-up transient is over, and must stay near d = r + h v.
    settle_time_s: float = 15.0
    max_mean_spacing_error_m: float = 3.0
    collisions: int = 0
    min_gap_m: float = math.inf
    min_time_gap_s: float = math.inf
    _in_collision: set = field(default_factory=set)
    _spacing_errors_m: list = field(default_factory=list)
    _speed_errors_mps: list = field(default_factory=list)
    _max_abs_accel_mps2: float = 0.0

    def observe(self, time_s: float, vehicle_id: str, gap_m: float | None, speed_mps: float,
                leader_speed_mps: float | None, accel_mps2: float) -> None:
        self._max_abs_accel_mps2 = max(self._max_abs_accel_mps2, abs(accel_mps2))
        if gap_m is None:
            return
        if gap_m <= 0 and vehicle_id not in self._in_collision:
            self.collisions += 1
            self._in_collision.add(vehicle_id)
        elif gap_m > 0:
            self._in_collision.discard(vehicle_id)
        self.min_gap_m = min(self.min_gap_m, gap_m)
        if speed_mps > MIN_SPEED_FOR_TIME_GAP_MPS:
            self.min_time_gap_s = min(self.min_time_gap_s, gap_m / speed_mps)
        if time_s < self.settle_time_s:
            return
        self._spacing_errors_m.append(gap_m - (self.standstill_m + self.time_gap_s * speed_mps))  # d = r + h v
        if leader_speed_mps is not None:
            self._speed_errors_mps.append(speed_mps - leader_speed_mps)

    def metrics(self) -> dict[str, float]:
        """The spacing and speed errors as `coopdrive score` defines them (metrics.error_stats), after the
        settle time."""
        figures = {
            "collisions": float(self.collisions),
            "min_gap_m": self.min_gap_m if math.isfinite(self.min_gap_m) else -1.0,
            "min_time_gap_s": self.min_time_gap_s if math.isfinite(self.min_time_gap_s) else -1.0,
            "max_abs_accel_mps2": self._max_abs_accel_mps2,
        }
        figures.update(error_stats(np.array(self._spacing_errors_m), "spacing_error", "m"))
        figures.update(error_stats(np.array(self._speed_errors_mps) * KMH_PER_MPS, "speed_error", "kmh"))
        return figures

    def verdict(self) -> tuple[bool, str]:
        if self.collisions:
            return False, f"{self.collisions} collision(s)"
        if self.min_gap_m <= self.standstill_m:
            return False, f"minimum gap {self.min_gap_m:.2f} m not above the standstill distance {self.standstill_m} m"
        if not self._spacing_errors_m:
            return False, f"too short to judge the following: spacing is judged after {self.settle_time_s:.0f} s"
        spacing = self.metrics()["spacing_error_m"]
        if spacing > self.max_mean_spacing_error_m:
            return False, (f"not following: mean spacing error {spacing:.2f} m after {self.settle_time_s:.0f} s "
                           f"exceeds {self.max_mean_spacing_error_m} m")
        return True, ""
