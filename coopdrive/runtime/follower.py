"""ClockFollower: the worker loop of every service but the clock master, on the wall clock or following the
simulator's clock.

Lockstep: the simulator (the clock master) publishes SimClock(step k) after its sensor data and waits for StepDone(k)
from every participant. A follower handles step k once every upstream service of its vehicle has reported step k
and every downstream one step k-1 (see pipeline.py); stepping.py sends what the step published with its marker."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from enum import Enum

from coopdrive.bus import Envelope
from coopdrive.runtime.context import RunnerContext
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.runtime.participants import ParticipantTracker
from coopdrive.runtime.rejoin import MidRunJoin
from coopdrive.runtime.step_wait import StepWait
from coopdrive.runtime.stepping import Stepper
from coopdrive.v1 import sim_pb2

# How long the loop waits for an event at most before it looks at its triggers or steps again.
IDLE_WAIT_S = 0.1


class ClockMode(Enum):
    WALL = "wall"
    SIM = "sim"


@dataclass(slots=True)
class _ReleasedStep:
    """What a follower needs of a lockstep SimClock, read out of the protobuf once."""

    step: int
    time_s: float
    step_s: float
    participants: frozenset[str]
    # "<vehicle>/<topic>" this service subscribes to -> the simulator's last sequence before the clock.
    sequences: dict[str, int]


class ClockFollower:
    def __init__(self, context: RunnerContext, steps: Stepper, clock_mode: ClockMode, step_wait: StepWait):
        self._context = context
        self._steps = steps
        self._clock_mode = clock_mode
        self._wait = step_wait
        self._join = MidRunJoin(steps.barrier)
        self._participant_tracker = ParticipantTracker()
        self._pending_clocks: deque[_ReleasedStep] = deque()
        # From the first simulator clock: lockstep or paced to wall time; None before it.
        self._lockstep: bool | None = None

    def run(self) -> None:
        events = self._context.events
        while not self._context.stopping:
            if self._clock_mode is ClockMode.WALL:
                timeout = min(self._steps.triggers.seconds_until_next(self._steps.clock.now_s()), IDLE_WAIT_S)
            else:
                timeout = IDLE_WAIT_S
            events.handle_burst(timeout, self)
            self.run_what_is_due()

    def handle_events(self, events: list[tuple[RuntimeEvent, object]]) -> None:
        for event in events:
            self._context.events.handle(event, self)

    @property
    def steps_pending(self) -> bool:
        """Whether run_what_is_due has anything to look at: lockstep clocks not yet handled (wall-clock triggers
        are always worth a look)."""
        return self._clock_mode is ClockMode.WALL or bool(self._pending_clocks)

    def run_what_is_due(self) -> None:
        """On the wall clock the triggers that are due; in simulated time the steps the barrier releases."""
        if self._clock_mode is ClockMode.WALL:
            self._steps.triggers.run_due(self._steps.clock.now_s())
        else:
            self._run_ready_steps()

    # ----- EventRole ------------------------------------------------------------------------
    def on_data(self, envelope: Envelope) -> None:
        self._steps.note_received(envelope)
        if self._clock_mode is ClockMode.SIM and self._lockstep is not False:
            # Lockstep (or not known yet): handled in step order, never in arrival order.
            self._steps.dispatcher.add(envelope)
        else:
            self._context.dispatch(envelope)

    def on_clock(self, clock: sim_pb2.SimClock) -> None:
        self._context.clock_subscription.check_step(clock.step_s)
        self._lockstep = clock.lockstep
        if clock.lockstep:
            self._queue_clock(clock)
            return
        self._steps.clock.set(clock.time_s)
        self._track_participants(clock.participants)
        for envelope in self._steps.dispatcher.eligible(clock.time_s):
            self._context.dispatch(envelope)
        self._steps.triggers.run_due(clock.time_s)

    def on_step_done(self, participant: str, step: int, next_step: int, sequences: dict[str, int]) -> None:
        self._join.on_marker(participant, step, next_step, sequences)

    def on_alive(self, participant: str, alive: bool) -> None:
        for handler in self._context.liveliness_handlers:
            handler(participant, alive)

    # ----- lockstep -------------------------------------------------------------------------
    def _track_participants(self, participants) -> None:
        for participant, alive in self._participant_tracker.update(participants):
            self.on_alive(participant, alive)

    def _queue_clock(self, clock: sim_pb2.SimClock) -> None:
        started = self._join.started
        joining = self._join.on_clock(clock.step, frozenset(clock.participants), clock.sequences)
        if not started and self._join.joined_step > 0:
            self._start_mid_run(clock)
            return
        if joining:
            self._steps.resend_last_marker()
            for participant in joining:
                self._steps.barrier.mark_done(participant, clock.step)  # it has nothing before its first step
        if clock.step <= self._steps.last_step:
            return
        # Few of the simulator's topics are ours: look those up rather than walk the whole protobuf map.
        counted = clock.sequences
        # Those joining take part from the next step on.
        released = _ReleasedStep(clock.step, clock.time_s, clock.step_s, frozenset(clock.participants) - joining,
                                 {key: counted[key] for key in self._steps.barrier.subscribed if key in counted})
        # Participants only leave the steps already queued (one that rejoins takes part from a later step): one
        # missing from the newest clock is gone for the older pending steps too, or this service would wait
        # forever for the step marker of a crashed one.
        for pending in self._pending_clocks:
            pending.participants &= released.participants
        if self._pending_clocks and self._pending_clocks[-1].step == released.step:
            self._pending_clocks[-1] = released  # re-sent with fewer participants after a crash
        else:
            self._pending_clocks.append(released)

    def _start_mid_run(self, clock: sim_pb2.SimClock) -> None:
        """Restarted after a crash: the run goes on from the step after this clock's (see MidRunJoin)."""
        start_s = (clock.step + 1) * clock.step_s
        self._steps.last_step = clock.step
        self._steps.clock.set(clock.time_s)
        self._steps.triggers.start_at(start_s)
        self._steps.dispatcher.start_at(start_s)
        self._context.log.info("joined the run at step %d (%.3f s)", clock.step + 1, start_s)

    def _run_ready_steps(self) -> None:
        barrier = self._steps.barrier
        while self._pending_clocks:
            released = self._pending_clocks[0]
            self._steps.step_s = released.step_s
            if not self._steps.triggers.any_due(released.time_s):
                self._pending_clocks.popleft()  # idle step: our last marker already covers it
                continue
            step, participants = released.step, released.participants
            if barrier.waits(step, participants) or not barrier.holds(released.sequences):
                if not self._wait.gives_up(step, participants):
                    return
            self._pending_clocks.popleft()
            self._steps.clock.set(released.time_s)
            self._track_participants(released.participants)
            self._steps.run_lockstep_step(released.step, released.time_s)
