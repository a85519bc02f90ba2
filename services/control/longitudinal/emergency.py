"""Emergency braking: a time-to-collision path outside the comfort limits.

For a target closing at dv = v - v_p > 0:
    TTC = gap / dv                                                                        (eq. E1)
    a_req = min(a_p, 0) - dv^2 / (2 (gap - margin))     (constant-deceleration stop behind the target)  (eq. E2)
Braking starts when TTC < ttc_emergency_s or when a_req is beyond the comfort deceleration, and is held until
every target has TTC > ttc_release_s and needs no more than the comfort deceleration (hysteresis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..profiles import LimitGains


@dataclass(frozen=True)
class EmergencyDecision:
    active: bool
    accel_mps2: float
    object_id: int = 0
    ttc_s: float = math.inf


class EmergencyBrake:
    def __init__(self, limits: LimitGains) -> None:
        self.limits = limits
        self.active = False

    @staticmethod
    def ttc_s(gap_m: float, ego_speed_mps: float, pred_speed_mps: float) -> float:
        closing = ego_speed_mps - pred_speed_mps
        if closing <= 0:
            return math.inf
        return max(gap_m, 0.0) / closing  # (eq. E1)

    def required_accel_mps2(self, gap_m: float, ego_speed_mps: float, pred_speed_mps: float, pred_accel_mps2: float) -> float:
        closing = ego_speed_mps - pred_speed_mps
        if closing <= 0:
            return 0.0
        room = gap_m - self.limits.stop_margin_m
        if room <= 0:
            return -math.inf
        return min(pred_accel_mps2, 0.0) - closing**2 / (2.0 * room)  # (eq. E2)

    def step(self, ego_speed_mps: float, targets: list[tuple[int, float, float, float]]) -> EmergencyDecision:
        """targets: (object_id, gap_m, pred_speed_mps, pred_accel_mps2 or 0)."""
        lim = self.limits
        trigger = release_blocked = False
        worst_need, worst_id, worst_ttc = 0.0, 0, math.inf
        for object_id, gap_m, pred_speed, pred_accel in targets:
            ttc = self.ttc_s(gap_m, ego_speed_mps, pred_speed)
            need = self.required_accel_mps2(gap_m, ego_speed_mps, pred_speed, pred_accel)
            beyond_comfort = need < -lim.max_decel_mps2
            trigger = trigger or ttc < lim.ttc_emergency_s or beyond_comfort
            release_blocked = release_blocked or ttc < lim.ttc_release_s or beyond_comfort
            if (need, ttc) < (worst_need, worst_ttc):
                worst_need, worst_id, worst_ttc = need, object_id, ttc
        self.active = trigger or (self.active and release_blocked)
        if not self.active:
            return EmergencyDecision(False, 0.0)
        accel = min(max(worst_need, -lim.emergency_decel_mps2), -lim.max_decel_mps2)
        return EmergencyDecision(True, accel, worst_id, worst_ttc)
