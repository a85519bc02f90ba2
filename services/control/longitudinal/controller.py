"""The longitudinal controller: every law that applies runs each step and the minimum command wins.

Per target: CACC while its V2V acceleration is fresh (age <= v2v_timeout_s), else dCACC once the range-rate
history gives an acceleration estimate, else ACC; the fallback time gap ramps up to
max(h + raise, mode floor) and back down when V2V returns. Cruise runs against the planner's desired speed.
min() over all of them is the safest command (KIT, GCDC 2011; DRIVERTIVE used the same rule over two targets).
The comfort shaper limits it; a separate TTC path may override it with harder braking.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from coopdrive.vehicle import SPACING

from ..profiles import VehicleProfile
from ..step_period import step_period_s
from .acc import RadarAcc, RajamaniAcc
from .cacc import LagCompensatedCacc
from .contracts import CruiseLaw, FollowingLaw
from .cruise import CruisePi
from .dcacc import Dcacc
from .drivertive import DrivertiveSpeed
from .emergency import EmergencyBrake, EmergencyTarget
from .ploeg import PloegCacc
from .shaper import CommandShaper
from .stop_line import StopLineApproach
from .types import (STANDSTILL_SPEED_MPS, AccLaw, CaccLaw, FollowInput, LongitudinalCommand, LongitudinalMode, Spacing,
                    SpeedLaw, Target)

# Below this speed a target's present time gap means nothing; a new track starts at the goal.
NEW_TARGET_MIN_SPEED_MPS = 1.0
# A new track never starts below this time gap: the laws divide by it, and a target inside the standstill
# distance has none at all.
MIN_START_TIME_GAP_S = 0.2

MODE = LongitudinalMode


@dataclass
class _Track:
    """What the controller remembers about one target between steps."""

    cacc: FollowingLaw
    dcacc: Dcacc
    acc: FollowingLaw
    mode: int = MODE.LONGITUDINAL_MODE_UNSPECIFIED
    time_gap_s: float = math.nan


@dataclass(frozen=True)
class _Choice:
    """A law's request in the min-select: its acceleration, its mode, and the target it follows."""

    accel_mps2: float
    mode: int
    target: Target | None = None


class LongitudinalController:
    def __init__(
        self,
        profile: VehicleProfile,
        cacc_law: CaccLaw = CaccLaw.OURS,
        acc_law: AccLaw = AccLaw.OURS,
        speed_law: SpeedLaw = SpeedLaw.PI,
    ) -> None:
        self.profile = profile
        self.cacc_law, self.acc_law, self.speed_law = cacc_law, acc_law, speed_law
        self.cruise: CruiseLaw = CruisePi(profile) if speed_law is SpeedLaw.PI else DrivertiveSpeed(profile)
        self.shaper = CommandShaper(profile.limits)
        self.emergency = EmergencyBrake(profile.limits)
        self.stop_line = StopLineApproach()
        self.rejected_inputs = 0
        self.last_rejection: str | None = None
        self._tracks: dict[int, _Track] = {}
        self._last_time_s: float | None = None

    def reset(self, command_mps2: float = 0.0, ego_speed_mps: float = 0.0) -> None:
        """Start again from the given applied command (e.g. when automation is engaged)."""
        self.shaper.reset(command_mps2)
        self.cruise.disengage()
        self.emergency.active = False
        self._tracks.clear()
        self._last_time_s = None

    def _new_track(self) -> _Track:
        p = self.profile
        cacc = LagCompensatedCacc(p.cacc, p.engine_lag_s) if self.cacc_law is CaccLaw.OURS else PloegCacc(p.ploeg)
        acc = RadarAcc(p.acc) if self.acc_law is AccLaw.OURS else RajamaniAcc(p.rajamani)
        return _Track(cacc=cacc, dcacc=Dcacc(p.cacc, p.dcacc, p.engine_lag_s), acc=acc)

    def _reject(self, reason: str) -> None:
        self.rejected_inputs += 1
        self.last_rejection = reason

    def _time_gap_goal_s(self, mode: int, planner_gap_s: float) -> float:
        sp = self.profile.spacing
        if mode == MODE.LONGITUDINAL_MODE_CACC:
            return planner_gap_s
        floor = sp.dcacc_time_gap_s if mode == MODE.LONGITUDINAL_MODE_DCACC else sp.acc_time_gap_s
        return max(planner_gap_s + sp.fallback_time_gap_raise_s, floor)

    def _follow(self, dt_s: float, time_s: float, t: Target, v: float, a: float, spacing: Spacing) -> tuple[float, int, FollowInput]:
        sp = self.profile.spacing
        track = self._tracks.get(t.object_id)
        is_new = track is None
        if track is None:
            track = self._tracks[t.object_id] = self._new_track()
        track.dcacc.observe(time_s, v, t.speed_mps - v)
        fresh = t.accel_mps2 is not None and t.v2v_age_s is not None and t.v2v_age_s <= sp.v2v_timeout_s
        if fresh:
            mode = MODE.LONGITUDINAL_MODE_CACC
        elif track.dcacc.ready():
            mode = MODE.LONGITUDINAL_MODE_DCACC
        else:
            mode = MODE.LONGITUDINAL_MODE_ACC
        goal = self._time_gap_goal_s(mode, spacing.time_gap_s)
        if is_new:
            # A target found closer than the goal (a cut-in, or a platoon formed at the CACC gap while the
            # planner still asks for more) starts at its present time gap and opens at the ramp rate: no jolt.
            now_s = (t.gap_m - spacing.standstill_m - t.extra_gap_m) / v if v > NEW_TARGET_MIN_SPEED_MPS else goal
            track.time_gap_s = min(goal, max(now_s, MIN_START_TIME_GAP_S))
        else:
            ramp = sp.time_gap_rate_sps * dt_s
            track.time_gap_s = min(max(goal, track.time_gap_s - ramp), track.time_gap_s + ramp)
        f = FollowInput(
            gap_m=t.gap_m,
            ego_speed_mps=v,
            ego_accel_mps2=a,
            pred_speed_mps=t.speed_mps,
            pred_accel_mps2=t.accel_mps2 if fresh else 0.0,
            standstill_m=spacing.standstill_m + t.extra_gap_m,
            time_gap_s=track.time_gap_s,
            pred_intended_accel_mps2=t.intended_accel_mps2 if fresh else None,
        )
        law: FollowingLaw = {MODE.LONGITUDINAL_MODE_CACC: track.cacc,
                             MODE.LONGITUDINAL_MODE_DCACC: track.dcacc}.get(mode, track.acc)
        if mode != track.mode:
            law.reset(self.shaper.last_mps2, f)
            track.mode = mode
        return law.step(dt_s, f), mode, f

    def step(
        self,
        time_s: float,
        ego_speed_mps: float,
        ego_accel_mps2: float,
        targets: Sequence[Target],
        desired_speed_mps: float,
        spacing: Spacing | None = None,
    ) -> LongitudinalCommand:
        """One control period. Units: s, m/s, m/s2. spacing may be the planner's SpacingPolicy message."""
        dt = self._period_s(time_s, ego_speed_mps, ego_accel_mps2, desired_speed_mps)
        spacing = self._spacing(spacing)
        cruise_u = self.cruise.step(dt, ego_speed_mps, desired_speed_mps)
        outputs = {"cruise": cruise_u}
        best = _Choice(cruise_u, MODE.LONGITUDINAL_MODE_CRUISE)
        valid = [t for t in targets if self._accepted(t)]
        for t in valid:
            if t.stop_line:
                u = outputs["stop_line"] = self.stop_line.step(t.gap_m, ego_speed_mps)
                choice = _Choice(u, MODE.LONGITUDINAL_MODE_STOP_LINE)
            else:
                u, mode, f = self._follow(dt, time_s, t, ego_speed_mps, ego_accel_mps2, spacing)
                outputs[f"{LongitudinalMode.Name(mode)}:{t.object_id}"] = u
                choice = _Choice(u, mode, t)
            if self._wins(choice.accel_mps2, best):
                best = choice
        seen = {t.object_id for t in valid if not t.stop_line}
        for object_id in [k for k in self._tracks if k not in seen]:
            del self._tracks[object_id]
        return self._apply(dt, best, valid, ego_speed_mps, desired_speed_mps, spacing, outputs)

    def _period_s(self, time_s: float, ego_speed_mps: float, ego_accel_mps2: float, desired_speed_mps: float) -> float:
        """The period since the last step; a gap in the calls too long, or backwards, restarts the controller."""
        for name, value in (("time_s", time_s), ("ego_speed_mps", ego_speed_mps),
                            ("ego_accel_mps2", ego_accel_mps2), ("desired_speed_mps", desired_speed_mps)):
            if not math.isfinite(value):
                self._reject(f"{name} is not finite")
                raise ValueError(f"longitudinal controller: {name} is not finite ({value})")
        dt, broke_off = step_period_s(self._last_time_s, time_s)
        if broke_off:
            self.reset(self.shaper.last_mps2, ego_speed_mps)
        self._last_time_s = time_s
        return dt

    def _spacing(self, spacing: Spacing | None) -> Spacing:
        """The planner's spacing; the spacing policy's where it gives none."""
        if spacing is None or spacing.time_gap_s <= 0:
            standstill_m = SPACING.standstill_m if spacing is None else spacing.standstill_m
            return Spacing(standstill_m, SPACING.cacc_time_gap_s)
        return Spacing(spacing.standstill_m, spacing.time_gap_s)

    def _accepted(self, t: Target) -> bool:
        reason = t.invalid_reason()
        if reason is not None:
            self._reject(reason)
        return reason is None

    def _apply(self, dt: float, best: _Choice, valid: list[Target], ego_speed_mps: float, desired_speed_mps: float,
               spacing: Spacing, outputs: dict[str, float]) -> LongitudinalCommand:
        """The emergency path may override the min-select's winner; the shaper limits what is applied. It judges
        only targets in our path: the follow laws keep the gap to a virtual target in the other lane."""
        decision = self.emergency.step(ego_speed_mps, [self._emergency_view(t) for t in valid if t.in_path])
        mode, target = best.mode, best.target
        if decision.active:
            applied = self.shaper.step(dt, decision.accel_mps2, emergency=True)
            mode = MODE.LONGITUDINAL_MODE_EMERGENCY_BRAKE
            target = next((t for t in valid if t.object_id == decision.object_id), target)
        else:
            applied = self.shaper.step(dt, best.accel_mps2)
        if best.mode == MODE.LONGITUDINAL_MODE_CRUISE and not decision.active:
            if self.cruise.engaged:
                self.cruise.track(dt, applied)
            else:
                self.cruise.engage(applied, ego_speed_mps)
        else:
            self.cruise.disengage()
        if mode != MODE.LONGITUDINAL_MODE_EMERGENCY_BRAKE and ego_speed_mps < STANDSTILL_SPEED_MPS and applied <= 0:
            mode = MODE.LONGITUDINAL_MODE_STANDSTILL
        cmd = LongitudinalCommand(
            accel_request_mps2=applied, mode=mode, emergency_brake=decision.active, cruise_speed_mps=desired_speed_mps,
            law_outputs_mps2=outputs, response_time_constant_s=self.profile.engine_lag_s,
            response_time_delay_s=self.profile.actuation_delay_s)
        if target is not None:
            track = self._tracks.get(target.object_id)
            h = track.time_gap_s if track is not None else spacing.time_gap_s
            cmd.target_object_id, cmd.gap_m, cmd.time_gap_s = target.object_id, target.gap_m, h
            cmd.desired_gap_m = spacing.standstill_m + target.extra_gap_m + h * ego_speed_mps
        return cmd

    def _wins(self, u: float, best: _Choice) -> bool:
        """Min-select over what the shaper would apply: above the comfort acceleration every law commands the
        same, so a follow law wanting more than the limit must not hand the vehicle to cruise, whose gentle
        reference model would then cap its acceleration below its braking and let it fall behind."""
        cap = self.profile.limits.max_accel_mps2
        u, best_u = min(u, cap), min(best.accel_mps2, cap)
        return u < best_u or (u == best_u and best.mode == MODE.LONGITUDINAL_MODE_CRUISE)

    def _emergency_view(self, t: Target) -> EmergencyTarget:
        """A stop line's gap already ends at its stopping point, so the vehicle margin is not taken off twice."""
        if t.stop_line:
            return EmergencyTarget(t.object_id, t.gap_m + self.profile.limits.stop_margin_m, 0.0)
        measured, reported = self._pred_accel_for_ttc(t)
        # The request leads the measurement by the predecessor's driveline lag: whichever brakes harder counts.
        if t.intended_accel_mps2 is not None and t.intended_accel_mps2 < measured:
            measured, reported = t.intended_accel_mps2, True
        return EmergencyTarget(t.object_id, t.gap_m, t.speed_mps, measured, reported)

    def _pred_accel_for_ttc(self, t: Target) -> tuple[float, bool]:
        """The predecessor's acceleration and whether it reported it over V2V (fresh) or we estimated it."""
        if t.accel_mps2 is not None and t.v2v_age_s is not None and t.v2v_age_s <= self.profile.spacing.v2v_timeout_s:
            return t.accel_mps2, True
        track = self._tracks.get(t.object_id)
        estimate = track.dcacc.estimator.estimate_mps2() if track is not None else None
        return (0.0 if estimate is None else estimate), False
