"""Out-of-sequence measurements: a short history of inputs and filter snapshots.

A GNSS fix arrives tens of milliseconds after its sample time, when odometry up to the present has
already been fused. The buffer restores the filter as it was just before the fix's sample time, fuses the
fix there, and re-applies the later inputs, so every measurement acts at the instant it describes.
"""

from __future__ import annotations

import bisect
import enum
from collections import Counter
from dataclasses import dataclass, field
from typing import Any, Callable, Generic, TypeVar

Snapshot = TypeVar("Snapshot")


class Insertion(enum.Enum):
    IN_ORDER = "in_order"
    REPLAYED = "replayed"
    TOO_OLD = "too_old"


@dataclass(order=True)
class _Entry(Generic[Snapshot]):
    time_s: float
    sequence: int
    event: Any = field(compare=False)
    after: Any = field(compare=False, default=None)


class ReplayBuffer(Generic[Snapshot]):
    """apply(time_s, event) fuses one input; snapshot()/restore() save and set the filter state."""

    def __init__(self, apply: Callable[[float, Any], None], snapshot: Callable[[], Snapshot],
                 restore: Callable[[Snapshot], None], horizon_s: float) -> None:
        self._apply = apply
        self._snapshot = snapshot
        self._restore = restore
        self.horizon_s = horizon_s
        self._entries: list[_Entry] = []
        self._sequence = 0
        self.counts: Counter[Insertion] = Counter()
        self.replayed_events = 0

    @property
    def latest_time_s(self) -> float | None:
        return self._entries[-1].time_s if self._entries else None

    def add(self, time_s: float, event: Any) -> Insertion:
        self._sequence += 1
        entry = _Entry(time_s, self._sequence, event)
        if not self._entries or time_s >= self._entries[-1].time_s:
            self._run(entry)
            self._entries.append(entry)
            self._trim()
            return self._count(Insertion.IN_ORDER)
        index = bisect.bisect_right(self._entries, entry)
        if index == 0:
            return self._count(Insertion.TOO_OLD)
        self._restore(self._entries[index - 1].after)
        self._entries.insert(index, entry)
        for later in self._entries[index:]:
            self._run(later)
        self.replayed_events += len(self._entries) - index - 1
        return self._count(Insertion.REPLAYED)

    def clear(self) -> None:
        self._entries.clear()

    def _run(self, entry: _Entry) -> None:
        self._apply(entry.time_s, entry.event)
        entry.after = self._snapshot()

    def _trim(self) -> None:
        cutoff_s = self._entries[-1].time_s - self.horizon_s
        drop = 0
        while drop < len(self._entries) - 1 and self._entries[drop].time_s < cutoff_s:
            drop += 1
        del self._entries[:drop]

    def _count(self, insertion: Insertion) -> Insertion:
        self.counts[insertion] += 1
        return insertion
