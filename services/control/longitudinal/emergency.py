"""Emergency braking: a time-to-collision path outside the comfort limits.

For a target at gap s, ego speed v, predecessor speed v_p and predecessor deceleration a_p <= 0 held to standstill:
    TTC = s / (v - v_p)                                   for a closing target           (eq. E1)
The deceleration that ends at the release gap m = stop_margin_m + release_margin_m, with room = s - m and the
predecessor's stopping distance s_p = v_p^2 / (2 |a_p|):
    a_stop = -v^2 / (2 (room + s_p))      both stop; the gap is smallest at the end       (eq. E2a)
    a_req  = a_p - (v - v_p)^2 / (2 room) when ego must brake harder than the predecessor (eq. E2b)
E2a holds while a_stop >= a_p, E2b otherwise; a_p = 0 makes E2b the plain constant-speed case.
Braking starts when TTC < ttc_emergency_s or when comfort braking would let the gap fall below the margin within
brake_horizon_s (eq. E3, the gap's minimum over the horizon under both decelerations). It is held until every
target has TTC > ttc_release_s and comfort braking keeps release_margin_m more than the margin, or keeps the gap
from shrinking at all (hysteresis).
A short horizon keeps a predecessor's brief hard braking, such as a speed oscillation, with the comfort laws.
A moving predecessor that reports over V2V (CAM, iCLCM) a deceleration harder than hard_braking_mps2 (the EEBL
trigger) starts it at once, braking at least as hard as the predecessor (eq. E4): a follower whose driveline needs
a second to build up braking cannot wait for the horizon to see a stop coming. A deceleration we only estimate
from our own sensors' speeds goes to the horizon test: differentiated from a young track's speed it is noise, and
as a trigger of its own it braked a platoon hard behind a phantom object.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..profiles import LimitGains
from .types import STANDSTILL_SPEED_MPS


@dataclass(frozen=True)
class EmergencyTarget:
    """What the emergency path needs of one target; accel_mps2 <= 0 is held to standstill, and accel_reported
    says it came over V2V from the predecessor itself rather than from our estimate."""

    object_id: int
    gap_m: float
    speed_mps: float
    accel_mps2: float = 0.0
    accel_reported: bool = False


@dataclass(frozen=True)
class EmergencyDecision:
    active: bool
    accel_mps2: float
    object_id: int = 0
    ttc_s: float = math.inf


def _travel_m(speed_mps: float, accel_mps2: float, t_s: float) -> float:
    """Distance covered in t_s at a constant acceleration, stopping (not reversing) at zero speed."""
    if accel_mps2 < 0:
        t_s = min(t_s, speed_mps / -accel_mps2)
    return speed_mps * t_s + 0.5 * accel_mps2 * t_s * t_s


def _speed_mps(speed_mps: float, accel_mps2: float, t_s: float) -> float:
    return max(speed_mps + accel_mps2 * t_s, 0.0)


def min_gap_within_m(gap_m: float, ego_speed_mps: float, ego_accel_mps2: float, pred_speed_mps: float,
                     pred_accel_mps2: float, horizon_s: float) -> float:
    """The gap's minimum over [0, horizon_s] with both vehicles at constant acceleration until they stop (eq. E3).

    The gap is piecewise quadratic, so the minimum lies at a piece's end or where the two speeds are equal."""
    stops = [speed / -accel for speed, accel in ((ego_speed_mps, ego_accel_mps2), (pred_speed_mps, pred_accel_mps2))
             if accel < 0]
    edges = sorted({0.0, horizon_s, *(t for t in stops if t < horizon_s)})
    candidates = list(edges)
    for start, end in zip(edges, edges[1:]):
        middle = 0.5 * (start + end)
        ego_a = ego_accel_mps2 if _speed_mps(ego_speed_mps, ego_accel_mps2, middle) > 0 else 0.0
        pred_a = pred_accel_mps2 if _speed_mps(pred_speed_mps, pred_accel_mps2, middle) > 0 else 0.0
        if ego_a != pred_a:
            closing = _speed_mps(ego_speed_mps, ego_accel_mps2, start) - _speed_mps(pred_speed_mps, pred_accel_mps2, start)
            t_equal = start + closing / (pred_a - ego_a)
            if start < t_equal < end:
                candidates.append(t_equal)

    def gap_at(t_s: float) -> float:
        return gap_m + _travel_m(pred_speed_mps, pred_accel_mps2, t_s) - _travel_m(ego_speed_mps, ego_accel_mps2, t_s)

    return min(gap_at(t) for t in candidates)


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
        """The weakest constant acceleration that stops at the release gap behind the predecessor (eq. E2a/E2b), so
        braking ends where the path may let go."""
        pred_accel = min(pred_accel_mps2, 0.0)
        closing = ego_speed_mps - pred_speed_mps
        room = gap_m - self.limits.stop_margin_m - self.limits.release_margin_m
        if pred_accel < 0 and ego_speed_mps > 0:
            if room + pred_speed_mps**2 / (2.0 * -pred_accel) <= 0:
                return -math.inf
            both_stop = -(ego_speed_mps**2) / (2.0 * (room + pred_speed_mps**2 / (2.0 * -pred_accel)))  # (eq. E2a)
            if both_stop >= pred_accel:
                return both_stop
        if closing <= 0:
            return 0.0
        if room <= 0:
            return -math.inf
        return pred_accel - closing**2 / (2.0 * room)  # (eq. E2b)

    def comfort_spare_m(self, gap_m: float, ego_speed_mps: float, pred_speed_mps: float,
                        pred_accel_mps2: float) -> float:
        """How far the gap stays above the stop margin within the horizon while braking at the comfort limit
        (eq. E3); infinite when the gap does not shrink, however short it is (standing behind a stopped car)."""
        lim = self.limits
        lowest = min_gap_within_m(gap_m, ego_speed_mps, -lim.max_decel_mps2, pred_speed_mps,
                                  min(pred_accel_mps2, 0.0), lim.brake_horizon_s)  # (eq. E3)
        return math.inf if lowest >= gap_m else lowest - lim.stop_margin_m

    def step(self, ego_speed_mps: float, targets: list[EmergencyTarget]) -> EmergencyDecision:
        lim = self.limits
        trigger = release_blocked = False
        worst_need, worst_id, worst_ttc = 0.0, 0, math.inf
        for target in targets:
            object_id, gap_m = target.object_id, target.gap_m
            pred_speed, pred_accel = target.speed_mps, target.accel_mps2
            ttc = self.ttc_s(gap_m, ego_speed_mps, pred_speed)
            need = self.required_accel_mps2(gap_m, ego_speed_mps, pred_speed, pred_accel)
            # A moving predecessor braking as hard as an emergency brake (EEBL) is matched at once (eq. E4):
            # by the time the horizon sees it, a driveline that needs a second to build up braking is late.
            # Both must be moving: a standing car's speed jitters around zero while its CAM still reports
            # the last deceleration, and a trigger on that noise toggles the mode at standstill.
            moving = pred_speed > STANDSTILL_SPEED_MPS and ego_speed_mps > STANDSTILL_SPEED_MPS
            hard = target.accel_reported and moving and pred_accel <= -lim.hard_braking_mps2
            if hard:
                need = min(need, pred_accel)
            spare_m = self.comfort_spare_m(gap_m, ego_speed_mps, pred_speed, pred_accel)
            trigger = trigger or hard or ttc < lim.ttc_emergency_s or spare_m < 0.0
            release_blocked = release_blocked or hard or ttc < lim.ttc_release_s or spare_m < lim.release_margin_m
            if (need, ttc) < (worst_need, worst_ttc):
                worst_need, worst_id, worst_ttc = need, object_id, ttc
        self.active = trigger or (self.active and release_blocked)
        if not self.active:
            return EmergencyDecision(False, 0.0)
        accel = min(max(worst_need, -lim.emergency_decel_mps2), -lim.max_decel_mps2)
        return EmergencyDecision(True, accel, worst_id, worst_ttc)
