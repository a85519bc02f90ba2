"""ParticipantTracker: liveliness in simulated time, derived from the clock's participant list.

On the vehicle, a service learns who is alive from Zenoh liveliness tokens, whenever they change.
In simulation that timing would make runs differ, so services learn it from each SimClock
instead, in step order: the simulator keeps the list current (it drops a participant whose token
disappears), and replay reads the same lists from the recording.
"""

from __future__ import annotations

from coopdrive.bus.keys import WORLD_ID

SIMULATOR = f"{WORLD_ID}/sim"


class ParticipantTracker:
    def __init__(self) -> None:
        self._alive: set[str] = set()

    def update(self, participants) -> list[tuple[str, bool]]:
        """The liveliness changes since the last clock, sorted, as (participant, alive)."""
        now_alive = {SIMULATOR, *participants}
        if now_alive == self._alive:
            return []  # every step but the first and a crash's
        changes = [(p, True) for p in sorted(now_alive - self._alive)]
        changes += [(p, False) for p in sorted(self._alive - now_alive)]
        self._alive = now_alive
        return changes
