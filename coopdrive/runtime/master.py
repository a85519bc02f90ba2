"""ClockMaster: the simulator's side of time. Steps the world in lockstep or paced to wall time.

It works through the runtime's public parts: the service's context (events, stopping, logging), the Stepper (a
step, the clock it publishes, the barrier) and the StepWait every follower uses too."""

from __future__ import annotations

import time
from dataclasses import dataclass

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.bus import Envelope
from coopdrive.runtime.context import RunnerContext
from coopdrive.runtime.step_wait import StepWait
from coopdrive.runtime.stepping import Stepper
from coopdrive.v1 import sim_pb2

# Subscriptions of freshly started peers take a moment to reach the publishers.
SETTLE_S = 0.3
# How long the master waits for an event at most before it looks at its steps again: while participants come up,
# and while a step waits for its markers.
STARTUP_POLL_S = 0.05
STEP_POLL_S = 0.5
# How long a crash may take to end the service's process (its liveliness token gone).
CRASH_TIMEOUT_S = 30.0


@dataclass(frozen=True)
class Outage:
    """A participant's process killed before step crash_step and started again before restart_step (None:
    never): the same steps whatever the wall clock, so a seed still gives one run."""

    participant: str
    crash_step: int
    restart_step: int | None = None


class ClockConfig(BaseModel):
    """How the simulated clock runs: what the clock master's owner configures (the simulator's config has it)."""

    # A misspelt setting is an error, as it was when the settings were a dataclass.
    model_config = ConfigDict(extra="forbid")

    step_s: float = 0.01
    lockstep: bool = True
    # Never run ahead of the wall clock scaled by realtime_factor (1.0 = real time; --realtime). With lockstep
    # too, a machine too slow for real time runs slower instead of starving the stack.
    paced: bool = False
    realtime_factor: float = 1.0
    # "<vehicle>/<service>" of every service in the barrier.
    participants: list[str] = Field(default_factory=list)
    startup_timeout_s: float = 60.0
    # How long the clock holds for a service_crash's restarted process to come back before going on without it. A
    # restart is a whole process start, at whatever load the machine has: given up on, the service is gone from
    # the rest of the run (seen twice in a loaded suite, where a restarted control never published again).
    restart_timeout_s: float = 180.0


class ClockSettings(ClockConfig):
    """A clock master's settings: its owner's configuration and what the owner derives for this run."""

    # Steps between a command's step and the step that applies it. 2 lets the simulator compute
    # step k+1 while the stacks still work on step k (two steps in flight on two cores); the
    # world model subtracts the extra step from the actuators' dead time.
    feedback_delay_steps: int = 1
    outages: list[Outage] = Field(default_factory=list)


class ParticipantsMissing(RuntimeError):
    pass


class ClockMaster:
    class Driven:
        """Mixin for the one service that owns simulated time."""

        def clock_settings(self) -> ClockSettings:
            raise NotImplementedError

        def on_clock_started(self, wall_start_monotonic_s: float) -> None:
            """Called once every participant is up, just before step 0."""

        def on_participant_lost(self, participant: str) -> None:
            """Called when a participant's liveliness token disappears mid-run."""

        def on_clock_failed(self, reason: str) -> None:
            """Called when the run cannot start (a participant never came up), before the error propagates."""

        def on_outage(self, participant: str, restart: bool) -> None:
            """An Outage falls due: have the participant's process killed (restart: started again). The clock
            holds until its liveliness token is gone (restart: back)."""

    def __init__(self, service: "ClockMaster.Driven", context: RunnerContext, steps: Stepper, step_wait: StepWait):
        self._service = service
        self._context = context
        self._steps = steps
        self._wait = step_wait
        self._settings = ClockSettings()
        self._participants: list[str] = []
        self._alive: set[str] = set()
        self._step = 0
        self.wall_time_s = 0.0

    @property
    def participants(self) -> list[str]:
        return list(self._participants)

    def run(self) -> None:
        # Read once the service has started: how many steps it can pipeline may depend on the world it loaded.
        self._settings = self._service.clock_settings()
        self._participants = list(self._settings.participants)
        lag = max(1, self._settings.feedback_delay_steps)
        self._steps.dispatcher.feedback_lag_s = (lag - 1) * self._settings.step_s
        try:
            self._wait_for_participants()
        except ParticipantsMissing as error:
            self._service.on_clock_failed(str(error))
            raise
        wall_start = time.monotonic()
        self._service.on_clock_started(wall_start)
        while not self._context.stopping:
            time_s = self._step * self._settings.step_s
            if self._settings.lockstep:
                lag = max(1, self._settings.feedback_delay_steps)
                if self._step >= lag and not self._wait_for_step_done(self._step - lag):
                    break
            if not self._carry_out_outages():
                break
            if self._settings.paced or not self._settings.lockstep:
                if not self._wait_until(wall_start + time_s / self._settings.realtime_factor):
                    break
            self._steps.run_step(self._step, time_s)
            self._publish_clock()
            self._step += 1

    def _publish_clock(self, to_all: bool = False) -> None:
        """To the followers whose triggers can run in this step (KeyLayout.clock_step); `to_all` (and every
        clock of a run not in lockstep) to each of them."""
        clock = sim_pb2.SimClock(step=self._step, time_s=self._context.now_s(), step_s=self._settings.step_s,
                                 lockstep=self._settings.lockstep, participants=self._participants,
                                 sequences=self._steps.published_sequences)
        layout = self._context.bus.layout
        to_all = to_all or not self._settings.lockstep
        self._steps.publish_clock(clock, layout.clock_to_all() if to_all else layout.clock_step(self._step))

    def _wait_for_participants(self) -> None:
        deadline = time.monotonic() + self._settings.startup_timeout_s
        while not self._context.stopping and not set(self._participants) <= self._alive:
            if time.monotonic() > deadline:
                missing = sorted(set(self._participants) - self._alive)
                raise ParticipantsMissing(f"services did not come up: {', '.join(missing)}")
            self._handle_one(STARTUP_POLL_S)
        self._wait_for(lambda: False, SETTLE_S)

    def _wait_for(self, condition, timeout_s: float) -> bool:
        """Handles events until condition() holds (True) or timeout_s has passed or the run stops (False)."""
        deadline = time.monotonic() + timeout_s
        while not condition():
            remaining = deadline - time.monotonic()
            if remaining <= 0 or self._context.stopping:
                return False
            self._handle_one(min(remaining, STARTUP_POLL_S))
        return True

    def _carry_out_outages(self) -> bool:
        """The crashes and restarts due before this step; False when the run stopped meanwhile."""
        for outage in self._settings.outages:
            if outage.crash_step == self._step:
                self._crash(outage.participant)
            if outage.restart_step == self._step:
                self._restart(outage.participant)
        return not self._context.stopping

    def _crash(self, participant: str) -> None:
        # What the service sent up to the last step is in before it dies, so its last outputs do not depend on
        # how far it had got when the kill came.
        if self._settings.lockstep and self._step > 0 and not self._wait_for_step_done(self._step - 1):
            return
        self._service.on_outage(participant, restart=False)
        if not self._wait_for(lambda: participant not in self._alive, CRASH_TIMEOUT_S):
            self._context.log.warning("%s is still alive after its crash; dropped from the run", participant)
        self.on_alive(participant, False)  # nothing more when its token's end already did it

    def _restart(self, participant: str) -> None:
        self._service.on_outage(participant, restart=True)
        if not self._wait_for(lambda: participant in self._alive, self._settings.restart_timeout_s):
            self._context.log.warning("%s did not come back within %.0f s; continuing without it", participant,
                                      self._settings.restart_timeout_s)
            return
        self._wait_for(lambda: False, SETTLE_S)  # its subscriptions reach the publishers first
        self._participants = [p for p in self._settings.participants if p in self._participants or p == participant]
        self._steps.barrier.mark_done(participant, self._step - 1)  # it has nothing before its first step
        self._service.count("participants_restarted")
        self._context.log.info("%s rejoined the run at step %d", participant, self._step)
        # A clock listing it for the first time tells it the step it joins from and has the others re-send their
        # last step markers to it (see MidRunJoin).
        self._resend_last_clock()

    def _wait_for_step_done(self, step: int) -> bool:
        """Waits until every participant has reported `step` (the barrier lets step + 1 go), or the wait gives up
        on a lost message (step_wait.py); False when the run stopped meanwhile."""
        while not self._context.stopping:
            running = set(self._participants)
            if not self._steps.barrier.waits(step + 1, running) or self._wait.gives_up(step + 1, running):
                return True
            self._context.events.handle_burst(STEP_POLL_S, self)
        return False

    def _wait_until(self, wall_deadline: float) -> bool:
        while not self._context.stopping:
            remaining = wall_deadline - time.monotonic()
            if remaining <= 0:
                return True
            self._handle_one(remaining)
        return False

    def _handle_one(self, timeout_s: float) -> None:
        events = self._context.events
        events.handle(events.next_event(timeout_s), self)

    # ----- EventRole ------------------------------------------------------------------------
    def on_data(self, envelope: Envelope) -> None:
        self._steps.note_received(envelope)
        self._steps.dispatcher.add(envelope)

    def on_clock(self, clock: sim_pb2.SimClock) -> None:
        """The master publishes the clock; it never follows one."""

    def on_step_done(self, participant: str, step: int, next_step: int, sequences: dict[str, int]) -> None:
        self._steps.barrier.mark_done(participant, step, next_step, sequences)

    def on_alive(self, participant: str, alive: bool) -> None:
        if alive:
            self._alive.add(participant)
            return
        self._alive.discard(participant)
        if participant not in self._participants:
            return
        self._participants.remove(participant)
        self._service.count("participants_lost")
        self._context.log.warning("%s left the run; continuing without it", participant)
        self._service.on_participant_lost(participant)
        # Followers blocked on the lost service's marker re-read the participant list.
        self._resend_last_clock()

    def _resend_last_clock(self) -> None:
        if self._step > 0 and self._settings.lockstep:
            self._step -= 1
            self._publish_clock(to_all=True)
            self._step += 1
