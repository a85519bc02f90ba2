"""SignalController: the state of every signal group of one intersection at any instant, and when each phase ends.

Each group cycles red-amber, green, amber, red (signal_plan.py). The plan runs on a cycle clock: the run's time less
the offset, less whatever time the clock was held to extend an actuated stage's green. A fixed-time plan never
holds it, so its phases are a function of time alone. Phase ends are given as a SPATEM states them (TS 103 301,
TimeChangeDetails): minEndTime the earliest the phase can end, maxEndTime the latest (an actuated green still
able to extend), likelyTime what the controller expects (no further extension).
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Collection

from coopdrive.services.sim.signal_plan import SignalPlan
from coopdrive.v1 import infrastructure_pb2 as pb

# Positions on the cycle closer than this are the same instant (float sums of durations and of time steps).
_SAME_S = 1e-6


class SignalAspect(enum.IntEnum):
    """What a signal head shows, by the MovementPhaseState a SPATEM sends for it (TS 103 301 / ISO TS 19091)."""

    RED = pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN
    RED_AMBER = pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT
    GREEN = pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED
    AMBER = pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE

    @property
    def must_stop(self) -> bool:
        """Red and red-amber both forbid passing the stop line (Vienna Convention on Road Signs, art. 23)."""
        return self in (SignalAspect.RED, SignalAspect.RED_AMBER)


@dataclass(frozen=True)
class SignalPhase:
    """One phase of a group; ends in the run's seconds."""

    aspect: SignalAspect
    min_end_s: float
    max_end_s: float
    likely_end_s: float


@dataclass(frozen=True)
class _Boundary:
    """Where on the cycle clock a group's aspect begins."""

    position_s: float
    aspect: SignalAspect


class SignalController:
    def __init__(self, plan: SignalPlan) -> None:
        self.plan = plan
        self.cycle_s = plan.cycle_s
        # Cycle-clock positions where each stage's green starts and ends.
        starts, position = [], 0.0
        for stage in plan.stages:
            starts.append(position)
            position += stage.green_s + plan.intergreen_s
        self._green_starts_s = starts
        self._green_ends_s = [start + stage.green_s for start, stage in zip(starts, plan.stages)]
        self._stage_of = {group: index for index, stage in enumerate(plan.stages) for group in stage.groups}
        self._boundaries = {group: self._group_boundaries(group) for group in plan.groups}
        self.held_s = 0.0
        self._extended_s = 0.0
        self._extending_stage: int | None = None
        self.time_s = 0.0

    @property
    def groups(self) -> list[int]:
        return self.plan.groups

    def _group_boundaries(self, group: int) -> list[_Boundary]:
        stage = self._stage_of[group]
        start, end = self._green_starts_s[stage], self._green_ends_s[stage]
        boundaries = [_Boundary(start, SignalAspect.GREEN), _Boundary(end, SignalAspect.AMBER),
                      _Boundary(end + self.plan.amber_s, SignalAspect.RED)]
        if self.plan.red_amber_s > 0:
            boundaries.append(_Boundary((start - self.plan.red_amber_s) % self.cycle_s, SignalAspect.RED_AMBER))
        return sorted(boundaries, key=lambda b: b.position_s)

    # ----- stepping -----------------------------------------------------------------------------------
    def cycle_position_s(self, time_s: float) -> float:
        return (time_s - self.plan.offset_s - self.held_s) % self.cycle_s

    def step(self, now_s: float, calling_groups: Collection[int] = ()) -> None:
        """Advance to now_s; calling_groups have a vehicle on their detector (actuated stages hold their green for
        them). A fixed-time plan ignores them."""
        dt_s = now_s - self.time_s
        self.time_s = now_s
        if dt_s <= 0.0:
            return
        stage = self._green_stage(now_s)
        if stage is None or stage != self._extending_stage:
            self._extending_stage, self._extended_s = stage, 0.0
        if stage is None:
            return
        ahead_s = (self._green_ends_s[stage] - self.cycle_position_s(now_s)) % self.cycle_s
        allowed_s = self.plan.stages[stage].max_extension_s - self._extended_s
        called = any(group in calling_groups for group in self.plan.stages[stage].groups)
        if called and ahead_s <= dt_s + _SAME_S and allowed_s > 0.0:
            # The green would end within this step: hold the cycle clock instead.
            hold_s = min(dt_s, allowed_s)
            self.held_s += hold_s
            self._extended_s += hold_s

    def _green_stage(self, time_s: float) -> int | None:
        position = self.cycle_position_s(time_s)
        for index, (start, end) in enumerate(zip(self._green_starts_s, self._green_ends_s)):
            if start - _SAME_S <= position < end - _SAME_S:
                return index
        return None

    # ----- what the heads show ----------------------------------------------------------------------------
    def aspect(self, group: int, time_s: float) -> SignalAspect:
        return self.phases(group, time_s, count=1)[0].aspect

    def phases(self, group: int, time_s: float, count: int = 4) -> list[SignalPhase]:
        """The current phase of a group and the count - 1 after it, with their end times; time_s is now (a fixed
        plan answers for any instant, an actuated one for its clock as stepped)."""
        if group not in self._boundaries:
            raise KeyError(f"signal group {group} is not in the plan (groups {self.groups})")
        boundaries = self._boundaries[group]
        position = self.cycle_position_s(time_s)
        current = max(range(len(boundaries)), key=lambda i: (boundaries[i].position_s <= position + _SAME_S,
                                                            boundaries[i].position_s))
        phases = []
        for k in range(count):
            aspect = boundaries[(current + k) % len(boundaries)].aspect
            end = boundaries[(current + k + 1) % len(boundaries)].position_s
            laps = math.floor(k / len(boundaries))
            ahead_s = (end - position) % self.cycle_s + laps * self.cycle_s
            if ahead_s < _SAME_S:
                ahead_s += self.cycle_s
            min_end_s = time_s + ahead_s
            max_end_s = min_end_s + self._extension_room_s(position, ahead_s)
            phases.append(SignalPhase(aspect, min_end_s, max_end_s, min_end_s))
        return phases

    def _extension_room_s(self, position_s: float, ahead_s: float) -> float:
        """How much later than its minimum a moment ahead_s on can come: the extensions still open to the greens
        that end before it or at it."""
        room_s = 0.0
        for index, end in enumerate(self._green_ends_s):
            until_end_s = (end - position_s) % self.cycle_s
            lap = 0
            while until_end_s < ahead_s + _SAME_S:
                # The green extending now has used some of its room; the next cycle's has all of it again.
                used_s = self._extended_s if index == self._extending_stage and lap == 0 else 0.0
                room_s += max(self.plan.stages[index].max_extension_s - used_s, 0.0)
                until_end_s += self.cycle_s
                lap += 1
        return room_s

    def next_red_s(self, group: int, time_s: float) -> float:
        """When the group's next red begins (the end of its amber), at the earliest; now if it is red."""
        phases = self.phases(group, time_s)
        if phases[0].aspect is SignalAspect.RED:
            return time_s
        return next(phase.min_end_s for phase in phases if phase.aspect is SignalAspect.AMBER)
