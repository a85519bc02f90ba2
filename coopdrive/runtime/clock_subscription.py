"""ClockSubscription: which of the simulator's lockstep clocks a follower takes."""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable
from typing import Callable

from coopdrive.bus import Bus
from coopdrive.v1 import sim_pb2

# How far a trigger's period may be from a whole number of steps and still count as one.
WHOLE_STEPS_TOLERANCE = 1e-6

log = logging.getLogger(__name__)


class ClockSubscription:
    """A follower takes the clocks of the steps its time triggers can run in, and every clock sent to all.

    A lockstep follower handles its data only on the steps where a trigger is due (its step marker promises
    quiet until then), so a 10 Hz planner needs one clock in five of a 50 Hz simulator. Which ones it can know
    only when told the simulator's step before the run (`step_s`). Without it, for a trigger whose period is not
    a whole number of steps or is added after start, and when the simulator turns out to step otherwise, it
    takes every clock: a clock too many costs one delivery, a clock too few would stall the run.
    """

    def __init__(self, bus: Bus, on_clock: Callable[[sim_pb2.SimClock], None], step_s: float | None):
        self._bus = bus
        self._on_clock = on_clock
        self._step_s = step_s
        self._keys: set[str] = set()

    def declare(self, trigger_periods_s: Iterable[float]) -> None:
        layout = self._bus.layout
        periods = [self._whole_steps(period_s) for period_s in trigger_periods_s]
        for key in [layout.clock_to_all(), *layout.clock_steps(periods)]:
            self._subscribe(key)

    def trigger_added(self) -> None:
        """A trigger added while running starts on whichever step it is added in: take every clock."""
        if self._keys:
            self._take_every_clock()

    def check_step(self, step_s: float) -> None:
        """Called with each clock: a simulator stepping otherwise than announced gets every clock taken."""
        if self._step_s is not None and not math.isclose(step_s, self._step_s, rel_tol=1e-9):
            log.warning("the simulator steps %.6f s, not the announced %.6f s: taking every clock", step_s,
                        self._step_s)
            self._step_s = None
            self._take_every_clock()

    def _whole_steps(self, period_s: float) -> int | None:
        if self._step_s is None or self._step_s <= 0:
            return None
        steps = round(period_s / self._step_s)
        return steps if steps >= 1 and abs(period_s / self._step_s - steps) < WHOLE_STEPS_TOLERANCE else None

    def _take_every_clock(self) -> None:
        for key in self._bus.layout.clock_steps([None]):
            self._subscribe(key)

    def _subscribe(self, key: str) -> None:
        if key not in self._keys:
            self._keys.add(key)
            self._bus.subscribe_key(key, lambda _key, clock: self._on_clock(clock))
