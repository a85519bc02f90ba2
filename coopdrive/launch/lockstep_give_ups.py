"""LockstepGiveUps: how often a run's services went on without a message lockstep promised them.

A run in which any did is not deterministic (a host so loaded that a process stalled for seconds, a lost
message), whatever its verdict says: the launcher reads every service's diagnostics and adds the sum to the result.
"""
from __future__ import annotations

import threading

from coopdrive.runtime.barrier import MESSAGE_WAIT_LIMIT_S, MESSAGES_GIVEN_UP_COUNTER
from coopdrive.v1 import diagnostics_pb2

# Every service's diagnostics, whatever its vehicle.
DIAGNOSTICS_KEYS = "coopdrive/*/diagnostics/*"
# What a give-up is, as the printed summary and the sweep's pass table say it.
GIVE_UP_MEANING = f"lockstep went on without a message it waited {MESSAGE_WAIT_LIMIT_S:g} s for"


class LockstepGiveUps:
    def __init__(self) -> None:
        self._lock = threading.Lock()
        # Diagnostics key (one per vehicle and service) -> its latest count; diagnostics go out once a second.
        self._by_key: dict[str, int] = {}

    def observe(self, key: str, message: diagnostics_pb2.Diagnostics) -> None:
        count = int(message.counters.get(MESSAGES_GIVEN_UP_COUNTER, 0))
        if count:
            with self._lock:
                self._by_key[key] = max(count, self._by_key.get(key, 0))

    def total(self) -> int:
        with self._lock:
            return sum(self._by_key.values())
