"""StepDispatcher: which received messages a service handles in a lockstep step, in which order.

The same rule runs live and in replay, which is why a replayed service produces exactly the
messages it produced live.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

from coopdrive.bus import Envelope
from coopdrive.runtime.pipeline import PIPELINE_RANK, UNRANKED, step_order

# Times are sums of step lengths; this absorbs their rounding.
TIME_EPSILON_S = 1e-9


@dataclass(slots=True)
class _Pending:
    sort_key: tuple
    envelope: Envelope

    def __lt__(self, other: _Pending) -> bool:
        # The heap's only comparison; the generated one wrapped each key in a tuple first. Keys are unique.
        return self.sort_key < other.sort_key


class StepDispatcher:
    def __init__(self, own_service: str, own_vehicle_id: str, feedback_lag_s: float = 0.0):
        self._own_rank = PIPELINE_RANK[own_service]
        # Feedback is handled at least this long after the step it was sent in (besides one step).
        self.feedback_lag_s = feedback_lag_s
        self._own_vehicle = own_vehicle_id
        self._pending: list[_Pending] = []
        self._arrivals = 0
        # Data sent before this time is dropped (see start_at).
        self._start_s = -math.inf

    def start_at(self, start_s: float) -> None:
        """A service that joins a run mid-way (restarted after a crash) handles only what was sent from its first
        step on: which older messages still reached its new subscriptions depends on wall timing."""
        self._start_s = start_s
        self._pending = [item for item in self._pending if item.sort_key[0] >= start_s - TIME_EPSILON_S]
        heapq.heapify(self._pending)

    def add(self, envelope: Envelope) -> None:
        header = envelope.message.header
        if header.sent_time_s < self._start_s - TIME_EPSILON_S:
            return
        self._arrivals += 1
        sort_key = (header.sent_time_s, *step_order(header, envelope.topic, envelope.vehicle_id), self._arrivals)
        heapq.heappush(self._pending, _Pending(sort_key, envelope))

    def __len__(self) -> int:
        return len(self._pending)

    def eligible(self, step_time_s: float) -> list[Envelope]:
        """Removes and returns, in deterministic order, what may be handled at step_time_s."""
        ready: list[_Pending] = []
        held: list[_Pending] = []
        while self._pending and self._pending[0].sort_key[0] <= step_time_s + TIME_EPSILON_S:
            item = heapq.heappop(self._pending)
            (ready if self._may_handle(item.envelope, step_time_s) else held).append(item)
        for item in held:
            heapq.heappush(self._pending, item)
        return [item.envelope for item in ready]

    def _may_handle(self, envelope: Envelope, step_time_s: float) -> bool:
        header = envelope.message.header
        sender_rank = PIPELINE_RANK.get(header.sender, UNRANKED)
        if sender_rank < self._own_rank:
            return True  # upstream of us: same-step data is already complete
        # Feedback from downstream (or a peer): only what it published in earlier steps.
        return header.sent_time_s < step_time_s - self.feedback_lag_s - TIME_EPSILON_S
