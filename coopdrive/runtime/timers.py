"""Time triggers: a handler that runs at a fixed period on whichever clock the service uses."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from coopdrive.runtime.dispatcher import TIME_EPSILON_S


@dataclass
class TimeTrigger:
    period_s: float
    handler: Callable[[float], None]
    next_due_s: float | None = None
    # Periods that passed without the handler running (the service was busy or late): skipped, not caught up
    # in a burst, and counted, as libcluon's time trigger reports its overruns.
    overruns: int = 0

    @property
    def name(self) -> str:
        return getattr(self.handler, "__name__", type(self.handler).__name__)

    def due(self, now_s: float) -> bool:
        return self.next_due_s is None or now_s >= self.next_due_s - TIME_EPSILON_S

    def fire(self, now_s: float) -> int:
        """Runs the handler; returns how many periods were missed before this one."""
        if self.next_due_s is None:
            self.next_due_s = now_s
        missed = max(0, math.floor((now_s - self.next_due_s) / self.period_s + TIME_EPSILON_S))
        self.next_due_s += (missed + 1) * self.period_s
        self.overruns += missed
        self.handler(now_s)
        return missed


class TriggerSet:
    def __init__(self, on_error: Callable[[TimeTrigger, Exception], None] | None = None,
                 on_overrun: Callable[[TimeTrigger, int], None] | None = None) -> None:
        """on_error: called with the trigger and the exception when a handler raises, and the other triggers
        still run; without it the exception propagates (a replay stops where the service failed).
        on_overrun: called with the trigger and the periods it missed when it fires late."""
        self._triggers: list[TimeTrigger] = []
        self._on_error = on_error
        self._on_overrun = on_overrun

    def add(self, period_s: float, handler: Callable[[float], None]) -> TimeTrigger:
        if not period_s > 0:
            raise ValueError(f"a time trigger needs a positive period, got {period_s}")
        trigger = TimeTrigger(period_s, handler)
        self._triggers.append(trigger)
        return trigger

    def start_at(self, start_s: float) -> None:
        """Triggers that have never fired first fire on their period's grid from time 0, at or after start_s: a
        service started mid-run (restarted after a crash) keeps the phase it had, and the simulator's clocks it
        takes (chosen by period from step 0, see ClockSubscription) stay the ones it needs."""
        for trigger in self._triggers:
            if trigger.next_due_s is None:
                trigger.next_due_s = math.ceil(start_s / trigger.period_s - TIME_EPSILON_S) * trigger.period_s

    def __iter__(self):
        return iter(self._triggers)

    def periods_s(self) -> list[float]:
        return [trigger.period_s for trigger in self._triggers]

    def run_due(self, now_s: float) -> None:
        for trigger in self._triggers:
            if not trigger.due(now_s):
                continue
            if self._on_error is None:
                self._fire(trigger, now_s)
                continue
            try:
                self._fire(trigger, now_s)
            except Exception as error:  # one failing period must not stop the service or its other triggers
                self._on_error(trigger, error)

    def _fire(self, trigger: TimeTrigger, now_s: float) -> None:
        missed = trigger.fire(now_s)
        if missed and self._on_overrun is not None:
            self._on_overrun(trigger, missed)

    def overruns(self) -> dict[str, int]:
        """Missed periods so far, by trigger (handler) name."""
        counts: dict[str, int] = {}
        for trigger in self._triggers:
            counts[trigger.name] = counts.get(trigger.name, 0) + trigger.overruns
        return counts

    def next_due_s(self) -> float | None:
        """When the next trigger is due; None when one has never fired (it is due at once)."""
        if not self._triggers or any(t.next_due_s is None for t in self._triggers):
            return None
        return min(t.next_due_s for t in self._triggers)

    def any_due(self, now_s: float) -> bool:
        return any(t.due(now_s) for t in self._triggers)

    def seconds_until_next(self, now_s: float) -> float:
        pending = [t.next_due_s - now_s for t in self._triggers if t.next_due_s is not None]
        if any(t.next_due_s is None for t in self._triggers):
            return 0.0
        return max(0.0, min(pending)) if pending else 1.0
