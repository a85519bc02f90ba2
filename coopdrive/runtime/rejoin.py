"""MidRunJoin: how a lockstep follower treats participants that join while the run goes on.

A service the launcher restarts after a crash starts mid-run. The simulator announces it with a clock of the
step before the one it joins at (ClockMaster._restart): the newcomer takes that step as its start, and every
other follower, seeing a participant the previous clock did not list, re-sends its last step marker so the
newcomer learns how far each of them is. Whatever was sent before the newcomer's start counts as lost to it
(the messages its new subscriptions happened to catch depend on wall timing): the markers of earlier steps set
its baseline rather than make it wait for their messages.
"""

from __future__ import annotations

from coopdrive.runtime.barrier import StepBarrier


class MidRunJoin:
    def __init__(self, barrier: StepBarrier):
        self._barrier = barrier
        # The participants of the latest clock; None before the first.
        self._participants: frozenset[str] | None = None
        # The first step this service handles (0 unless it joined mid-run).
        self.joined_step = 0
        # Step markers that came before the first clock, when it was not known whether they predate the start.
        self._early_markers: list[tuple] = []

    @property
    def started(self) -> bool:
        return self._participants is not None

    def on_clock(self, step: int, participants: frozenset[str], sequences) -> frozenset[str]:
        """The participants this clock lists for the first time: they take part from step + 1 on. A first clock
        after step 0 starts this service at step + 1, with everything the clock counts taken as sent before."""
        previous, self._participants = self._participants, participants
        if previous is None:
            if step > 0:
                self.joined_step = step + 1
                self._count_as_received(sequences)
            early, self._early_markers = self._early_markers, []
            for marker in early:
                self.on_marker(*marker)
            return frozenset()
        return participants - previous

    def on_marker(self, participant: str, step: int, next_step: int, sequences: dict[str, int]) -> None:
        if not self.started:
            self._early_markers.append((participant, step, next_step, sequences))
            return
        if step < self.joined_step:
            self._count_as_received(sequences)
        self._barrier.mark_done(participant, step, next_step, sequences)

    def _count_as_received(self, sequences) -> None:
        for key in self._barrier.subscribed:
            if key in sequences:
                self._barrier.mark_received(key, sequences[key])
