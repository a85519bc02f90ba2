"""The latest SPaT of every signal group heard, whether it has contradicted itself, and the pace each intersection's
SPATEMs come at (the median of its last gaps: coopdrive/v2x/expected_period.py), so that a slow roadside unit's
silence between two of its SPATEMs is not taken for a lost SPaT.

Checked on each SPATEM, against the group's own phases and against its previous SPATEM: minEndTime after
maxEndTime, likelyTime outside them, minEndTime moving earlier or maxEndTime later within the same phase (each is
a promise: the phase ends no sooner, no later), a phase ending before its minEndTime.
"""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.roadmap.intersection_lanes import intersection_key
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v2x.expected_period import ObservedPeriod
from coopdrive.v2x.timebase import MS_PER_S, ItsClock

from .phases import GroupTiming, group_timing, intersection_failed

GroupKey = tuple[int, int, int]  # region (0: none given), intersection id, signal group


@dataclass(frozen=True)
class Contradiction:
    at_s: float
    why: str


class SpatTracker:
    def __init__(self, clock: ItsClock, tolerance_s: float) -> None:
        self.clock = clock
        self.tolerance_s = tolerance_s
        self.latest: dict[GroupKey, GroupTiming] = {}
        self.contradictions: dict[GroupKey, Contradiction] = {}
        self._paces: dict[tuple[int, int], ObservedPeriod] = {}
        self._heard_s: dict[tuple[int, int], float] = {}

    def on_spatem(self, content: pb.SpatemContent, received_s: float) -> None:
        for intersection in content.intersections:
            region, number = intersection_key(intersection.id)
            self._observe_pace((region, number), received_s)
            failed = intersection_failed(intersection.status)
            for group in intersection.signal_groups:
                key = (region, number, group.signal_group)
                timing = group_timing(group, failed, received_s, self.clock)
                why = self._contradiction(self.latest.get(key), timing)
                if why:
                    self.contradictions[key] = Contradiction(received_s, why)
                self.latest[key] = timing

    def period_s(self, key: GroupKey) -> float | None:
        """How often the group's intersection sends SPATEMs, by their arrivals; None before its second."""
        pace = self._paces.get(key[:2])
        period_ms = None if pace is None else pace.period_ms()
        return None if period_ms is None else period_ms / MS_PER_S

    def _observe_pace(self, intersection: tuple[int, int], received_s: float) -> None:
        before_s = self._heard_s.get(intersection)
        self._heard_s[intersection] = received_s
        if before_s is not None:
            self._paces.setdefault(intersection, ObservedPeriod()).observe((received_s - before_s) * MS_PER_S)

    def _contradiction(self, before: GroupTiming | None, now: GroupTiming) -> str:
        tol = self.tolerance_s
        inner = next((why for phase in now.phases if (why := phase.contradiction(tol))), "")
        if inner or before is None or before.current is None or now.current is None:
            return inner
        old, new = before.current, now.current
        if old.state != new.state:
            ended_early = old.min_end_s is not None and now.received_s < old.min_end_s - tol
            return "phase ended before its minEndTime" if ended_early else ""
        if old.min_end_s is not None and new.min_end_s is not None and new.min_end_s < old.min_end_s - tol:
            return "minEndTime jumped back"
        if old.max_end_s is not None and new.max_end_s is not None and new.max_end_s > old.max_end_s + tol:
            return "maxEndTime jumped forward"
        return ""

    def find(self, intersection: tuple[int, int], signal_group: int) -> GroupKey | None:
        """The key SPaT is held under for a MAP's intersection: the same id, the same region where both give one."""
        region, number = intersection
        for key in ((region, number, signal_group), (0, number, signal_group)):
            if key in self.latest:
                return key
        return next((k for k in self.latest if k[1:] == (number, signal_group) and region == 0), None)
