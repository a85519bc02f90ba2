"""StepWait: how long a lockstep step may wait for what it counts, for the followers and the clock master alike.

A step waits for step markers and for the messages they count. A participant that does not send its marker holds
the run (it is warned about every STALL_WARNING_S, naming who holds it); a message lost on the way once every marker
is in would hold it forever, so after MESSAGE_WAIT_LIMIT_S the step goes on without it, at the cost of that one
message (counted and logged), as it would on the vehicle."""

from __future__ import annotations

import logging
import time
from collections.abc import Collection
from typing import Callable

from coopdrive.runtime.barrier import MESSAGE_WAIT_LIMIT_S, MESSAGES_GIVEN_UP_COUNTER, StepBarrier

STALL_WARNING_S = 10.0


class StepWait:
    def __init__(self, barrier: StepBarrier, log: logging.Logger, count: Callable[[str], None]):
        self._barrier = barrier
        self._log = log
        self._count = count
        # The step waited for, since when its markers are all in, and the last warning about it (or its start).
        self._step: int | None = None
        self._markers_in_at = self._warned_at = 0.0

    def gives_up(self, step: int, participants: Collection[str]) -> bool:
        """Called while `step` is blocked by the barrier: True when every marker is in and only counted messages
        have been missing for MESSAGE_WAIT_LIMIT_S."""
        now = time.monotonic()
        if self._step != step:
            self._step = step
            self._markers_in_at = self._warned_at = now
        markers_missing = self._barrier.missing(step, participants, markers_only=True)
        if markers_missing:
            self._markers_in_at = now
            if now - self._warned_at > STALL_WARNING_S:
                self._warned_at = now
                self._log.warning("step %d still waits for %s", step, ", ".join(markers_missing))
            return False
        if now - self._markers_in_at < MESSAGE_WAIT_LIMIT_S:
            return False
        self._count(MESSAGES_GIVEN_UP_COUNTER)
        self._log.warning("step %d: gave up waiting for messages counted by %s", step,
                          ", ".join(self._barrier.missing(step, participants)) or "the simulator's clock")
        return True
