"""StepBarrier: knows when every service this one takes data from has finished a step.

A service depends only on the publishers of the topics it subscribes to. It needs step k
finished by those upstream of it (lower pipeline rank) and step k-1 by those downstream
(feedback). A marker also promises quiet until the sender's next time trigger, so idle
steps cost nothing. Services with no data between them never wait for each other, so a vehicle's
pipeline overlaps consecutive steps on several cores; (step, rank) only ever decreases
along a wait, so the waits cannot form a cycle.
"""

from __future__ import annotations

from collections.abc import Collection

from coopdrive.runtime.pipeline import PIPELINE_RANK, split_participant

# How long a step whose markers are all in may wait for the messages they count. Going on without them keeps a run
# alive after a lost message, but a run that did is no longer deterministic: each time is counted under this name
# in the service's diagnostics, and the launcher sums them into the run's result.
MESSAGE_WAIT_LIMIT_S = 5.0
MESSAGES_GIVEN_UP_COUNTER = "lockstep_messages_given_up"


class StepBarrier:
    def __init__(self, own_service: str):
        self._own_rank = PIPELINE_RANK[own_service]
        self._done_step: dict[str, int] = {}
        self._promised_sequences: dict[str, dict[str, int]] = {}
        self._received_sequences: dict[str, int] = {}
        # Dependency -> how many steps behind ours it may be: 0 upstream, 1 downstream (feedback).
        self._lag_steps: dict[str, int] = {}
        # "<vehicle>/<topic>" this service subscribes to; only their sequences are awaited.
        self.subscribed: set[str] = set()
        # The dependency waits() last found holding the step up: asked first next time, since the simulator's
        # clock asks after every burst of events while it waits for a step, and that one is most often still out.
        self._last_waited_for: str | None = None

    def depend_on(self, participant: str) -> None:
        _, service = split_participant(participant)
        if service in PIPELINE_RANK and PIPELINE_RANK[service] != self._own_rank:
            self._lag_steps[participant] = 0 if PIPELINE_RANK[service] < self._own_rank else 1

    def depends_on(self, participant: str) -> bool:
        return participant in self._lag_steps

    def mark_done(self, participant: str, step: int, next_step: int = 0,
                  sequences: dict[str, int] | None = None) -> None:
        """Step `step` is finished, and nothing will come before `next_step` (0: the next step)."""
        covered = max(step, next_step - 1)
        if covered > self._done_step.get(participant, -1):
            self._done_step[participant] = covered
            self._promised_sequences[participant] = {
                key: value for key, value in (sequences or {}).items() if key in self.subscribed}

    def mark_received(self, vehicle_topic: str, sequence: int) -> None:
        if sequence > self._received_sequences.get(vehicle_topic, 0):
            self._received_sequences[vehicle_topic] = sequence

    def holds(self, sequences) -> bool:
        """True once every subscribed message counted in `sequences` has been received."""
        return all(self._received_sequences.get(key, 0) >= value
                   for key, value in sequences.items() if key in self.subscribed)

    def done_step(self, participant: str) -> int:
        return self._done_step.get(participant, -1)

    def waits(self, step: int, participants: Collection[str], markers_only: bool = False) -> bool:
        """Whether missing() would name anyone: asked on every burst of events, so it stops at the first."""
        last = self._last_waited_for
        if last is not None and last in participants and self._waits_for(last, self._lag_steps[last], step,
                                                                         markers_only):
            return True
        for participant, lag_steps in self._lag_steps.items():
            if participant in participants and self._waits_for(participant, lag_steps, step, markers_only):
                self._last_waited_for = participant
                return True
        return False

    def _waits_for(self, participant: str, lag_steps: int, step: int, markers_only: bool) -> bool:
        return self.done_step(participant) < step - lag_steps or (
            not markers_only and not self.holds(self._promised_sequences.get(participant, {})))

    def missing(self, step: int, participants: Collection[str], markers_only: bool = False) -> list[str]:
        """Running dependencies whose step marker (and the messages it counts, unless markers_only) this
        service still needs before handling `step`, sorted. Called on every event: pass a set."""
        return sorted(participant for participant, lag_steps in self._lag_steps.items()
                      if participant in participants and self._waits_for(participant, lag_steps, step, markers_only))
