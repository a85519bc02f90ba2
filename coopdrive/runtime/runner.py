"""ServiceRunner: runs one Service on a live bus, with wall, simulated or lockstep time.

Zenoh callbacks only enqueue; a single worker loop handles every message and time trigger,
so a service's code never runs on two threads at once.

Lockstep: the simulator (the clock master) publishes SimClock(step k) after its sensor data
and waits for StepDone(k) from every participant. A follower handles step k once every
upstream service of its vehicle has reported step k and every downstream one step k-1
(see pipeline.py). The StepDone rides as the attachment of the step's last message on each
stepped topic (its own @step key for a topic the step left quiet); it counts the messages it
covers, so a follower also waits for any still on their way.
"""

from __future__ import annotations

import functools
import logging
import math
import os
import queue
import signal
import threading
import time
from collections import defaultdict, deque
from dataclasses import dataclass
from enum import Enum
from typing import Callable, Protocol

from google.protobuf.message import DecodeError, Message

from coopdrive.bus import Bus, BusConfig, Envelope
from coopdrive.bus.topics import stepped_topics_of, topic_named
from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.barrier import MESSAGE_WAIT_LIMIT_S, MESSAGES_GIVEN_UP_COUNTER, StepBarrier
from coopdrive.runtime.clock import SimulationClock, WallClock
from coopdrive.runtime.clock_subscription import ClockSubscription
from coopdrive.runtime.dispatcher import TIME_EPSILON_S, StepDispatcher
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.runtime.handler_ledger import HandlerLedger, handler_name
from coopdrive.runtime.launcher_watch import launched_by_a_run
from coopdrive.runtime.master import STALL_WARNING_S, ClockMaster
from coopdrive.runtime.participants import ParticipantTracker
from coopdrive.runtime.pipeline import participant_name
from coopdrive.runtime.profiling import WorkerProfile
from coopdrive.runtime.rejoin import MidRunJoin
from coopdrive.runtime.service import SequenceCounter, Service, ServiceConfig
from coopdrive.runtime.signal_wait import wait_hearing_signals
from coopdrive.runtime.timers import TriggerSet
from coopdrive.v1 import diagnostics_pb2, sim_pb2

DIAGNOSTICS_PERIOD_S = 1.0
# A periodic handler that keeps failing logs its traceback on the first and then every this many failures.
TRIGGER_FAILURE_LOG_EVERY = 500
# A finished clock master waits this long at most for its launcher to stop it (see _linger_for_the_launcher).
MASTER_LINGER_S = 60.0


class ClockMode(Enum):
    WALL = "wall"
    SIM = "sim"


class EventInbox(Protocol):
    """Where a service's events are put: its own queue, or its entry in a SharedWorker's."""

    def put(self, item) -> None: ...


@dataclass(slots=True)
class _ReleasedStep:
    """What a follower needs of a lockstep SimClock, read out of the protobuf once."""

    step: int
    time_s: float
    step_s: float
    participants: frozenset[str]
    # "<vehicle>/<topic>" this service subscribes to -> the simulator's last sequence before the clock.
    sequences: dict[str, int]


class ServiceRunner:
    opens_hardware = True

    def __init__(self, service_cls: type[Service], config: ServiceConfig, vehicle_id: str,
                 bus_config: BusConfig | None, clock_mode: ClockMode = ClockMode.WALL, bus: Bus | None = None,
                 clock_step_s: float | None = None, inbox: EventInbox | None = None):
        """`bus`: an existing (shared) Bus to run on instead of opening one from `bus_config`.
        `clock_step_s`: the simulator's step, when known before the run (see ClockSubscription).
        `inbox`: where this service's events go when a SharedWorker handles them instead of its own loop."""
        self.vehicle_id = vehicle_id
        self.log = logging.getLogger(f"coopdrive.{service_cls.name}")
        self._service_name = service_cls.name
        self._clock_mode = clock_mode
        self._clock = WallClock() if clock_mode is ClockMode.WALL else SimulationClock()
        self._events: EventInbox = inbox if inbox is not None else queue.SimpleQueue()
        # CPU of this service's handling, kept by a SharedWorker; None: the worker thread's own CPU time.
        self.worker_cpu_s: float | None = None
        self._handlers: dict[str, list[tuple[str, Callable[[Envelope], None]]]] = defaultdict(list)
        self._ledger = HandlerLedger.from_environment(f"{vehicle_id}-{service_cls.name}")
        self._bus_subscriptions: set[tuple[str, str]] = set()
        self._liveliness_handlers: list[Callable[[str, bool], None]] = []
        self._participant_tracker = ParticipantTracker()
        self._triggers = TriggerSet(on_error=self._on_trigger_error, on_overrun=self._on_trigger_overrun)
        self._trigger_failures: dict[str, int] = {}
        self._sequence = SequenceCounter(service_cls.name)
        self._stop = threading.Event()
        # Set by SIGINT/SIGTERM: the process is asked to end, by its launcher or its user.
        self._signalled = threading.Event()
        self._stop_reason = ""
        self._started_monotonic = time.monotonic()
        self._dispatcher = StepDispatcher(service_cls.name, vehicle_id)
        self._barrier = StepBarrier(service_cls.name)
        self._join = MidRunJoin(self._barrier)
        # The last step marker sent, re-sent to a participant that joins mid-run.
        self._last_marker: sim_pb2.StepDone | None = None
        self._pending_clocks: deque[_ReleasedStep] = deque()
        # Lockstep: what a step publishes, held back until its marker can go with it (publish_step_done).
        self._step_outbox: list[tuple[str, str, Message]] | None = None
        self._stepped_topics = frozenset(stepped_topics_of(service_cls.name))
        self._last_step = -1
        # (step, since when) the next pending step has been blocked by the barrier.
        self._blocked_since: tuple[int, float] | None = None
        self._stall_warned_at = 0.0
        self._step_s = 0.0
        # From the first simulator clock: lockstep or paced to wall time; None before it.
        self._lockstep: bool | None = None
        self.bus = bus if bus is not None else Bus(bus_config)
        self._clock_subscription = ClockSubscription(
            self.bus, lambda clock: self._events.put((RuntimeEvent.CLOCK, clock)), clock_step_s)
        self.service = service_cls(config, self)
        self._master = ClockMaster(self) if isinstance(self.service, ClockMaster.Driven) else None

    # ----- ServiceContext -------------------------------------------------------------------
    def now_s(self) -> float:
        return self._clock.now_s()

    def subscribe(self, topic: str, handler: Callable[[Envelope], None], vehicle_id: str | None = None) -> None:
        source = vehicle_id or self.vehicle_id
        spec = topic_named(topic)
        stepped = source != "*" and spec.stepped
        if stepped:
            self._barrier.depend_on(participant_name(source, spec.publisher))
        if (source, topic) not in self._bus_subscriptions:
            self._bus_subscriptions.add((source, topic))
            if stepped:
                self._barrier.subscribed.add(f"{source}/{topic}")
            self.bus.subscribe(source, topic, self._on_data)
        if self._ledger is not None:
            handler = self._ledger.timed("topic", topic, handler)
        self._handlers[topic].append((source, handler))

    def publish(self, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        self.publish_for(self.vehicle_id, topic, message, sample_time_s)

    def publish_for(self, vehicle_id: str, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        """Publishes under another vehicle's namespace (the simulator feeds every vehicle)."""
        self._sequence.stamp(message, vehicle_id, topic, self._clock.now_s(), sample_time_s)
        if self._step_outbox is not None:
            self._step_outbox.append((vehicle_id, topic, message))  # sent with the step's marker
        else:
            self.bus.publish(vehicle_id, topic, message)

    def every(self, period_s: float, handler: Callable[[float], None]) -> None:
        if self._ledger is not None:
            handler = self._ledger.timed("timer", handler_name(handler), handler)
        self._triggers.add(period_s, handler)
        self._clock_subscription.trigger_added()

    def watch_liveliness(self, handler: Callable[[str, bool], None]) -> None:
        self._liveliness_handlers.append(handler)

    def call_soon(self, function: Callable[[], None]) -> None:
        if self._ledger is not None:
            function = self._ledger.timed("call", handler_name(function), function)
        self._events.put((RuntimeEvent.CALL, function))

    def request_stop(self, reason: str) -> None:
        self._stop_reason = reason
        self._stop.set()
        self._events.put((RuntimeEvent.STOP, None))

    # ----- life cycle -----------------------------------------------------------------------
    def run(self) -> str:
        """Runs until SIGINT/SIGTERM or request_stop; returns the stop reason."""
        if threading.current_thread() is threading.main_thread():
            for signum in (signal.SIGINT, signal.SIGTERM):
                signal.signal(signum, lambda sig, _frame: self.on_signal(signal.Signals(sig).name))
        profile = WorkerProfile.from_environment(f"{self.vehicle_id}-{self._service_name}")
        try:
            self.begin()
            with profile:
                if self._master is not None:
                    self._master.run()
                    self._linger_for_the_launcher()
                else:
                    self._follow()
        finally:
            self.end()
        return self._stop_reason

    def begin(self) -> None:
        """Starts the service and declares what the runtime needs on the bus; the last before events flow."""
        self.service.start()
        self._triggers.add(DIAGNOSTICS_PERIOD_S, self._publish_diagnostics)
        self._declare_runtime_entities()

    def end(self) -> None:
        try:
            self.service.stop()
        finally:
            self.bus.close()
            if self._ledger is not None:
                self._ledger.write(self.own_cpu_s)

    @property
    def own_cpu_s(self) -> float:
        """The CPU this service's handling has used: its share of a SharedWorker, or its own thread's."""
        return time.thread_time() if self.worker_cpu_s is None else self.worker_cpu_s

    @property
    def stop_reason(self) -> str:
        return self._stop_reason

    def on_signal(self, name: str) -> None:
        """SIGINT or SIGTERM (`name`) reached the process: its launcher or its user asks it to end."""
        self._signalled.set()
        self.request_stop(name)

    def _linger_for_the_launcher(self) -> None:
        """A clock master that ended the run itself (its scenario finished) keeps its bus open until the launcher
        that started it stops it (SIGTERM), at most MASTER_LINGER_S: what it published last, the result, may still
        wait in its send queue behind a loaded launcher's backlog, and closing the session would drop it.

        The launcher's SIGTERM may come before the master has finished its last step (the result is out, the
        step is not): it still counts."""
        if launched_by_a_run():
            wait_hearing_signals(self._signalled, MASTER_LINGER_S)

    def _declare_runtime_entities(self) -> None:
        layout = self.bus.layout
        if self._clock_mode is ClockMode.SIM and self._master is None:
            self._clock_subscription.declare(self._triggers.periods_s())
        for source, topic in sorted(self._bus_subscriptions):
            participant = self._awaited_publisher(source, topic)
            if participant is not None:
                on_marker = functools.partial(self._on_quiet_topic, participant)
                self.bus.subscribe_key(layout.step_done(source, topic), on_marker)
        if self._master is not None or (self._liveliness_handlers and self._clock_mode is ClockMode.WALL):
            # In simulation, followers learn liveliness from the clock (see participants.py).
            self.bus.watch_liveliness(layout.all_liveliness(), self._on_liveliness)
        self.bus.declare_queryable(layout.service_info(self.vehicle_id, self._service_name), self._service_info)
        # Last: the token tells the others that every subscription above is in place.
        self.bus.declare_token(layout.liveliness(self.vehicle_id, self._service_name))

    def _awaited_publisher(self, vehicle_id: str, topic: str) -> str | None:
        """The participant whose step markers this service waits for on `topic` of `vehicle_id`, if any."""
        spec = topic_named(topic)
        participant = participant_name(vehicle_id, spec.publisher)
        return participant if spec.stepped and self._barrier.depends_on(participant) else None

    def _on_data(self, envelope: Envelope) -> None:
        self._events.put((RuntimeEvent.DATA, envelope))
        if envelope.attachment is None:
            return
        participant = self._awaited_publisher(envelope.vehicle_id, envelope.topic)
        if participant is None:
            return
        marker = sim_pb2.StepDone()
        try:
            marker.ParseFromString(envelope.attachment)
        except DecodeError as error:
            self.service.count("bad_step_markers")
            self.log.warning("dropped a malformed step marker on %s/%s: %s", envelope.vehicle_id, envelope.topic, error)
            return
        self._on_step_marker(participant, marker)

    def _on_quiet_topic(self, participant: str, _key: str, marker: sim_pb2.StepDone) -> None:
        self._on_step_marker(participant, marker)

    def _on_step_marker(self, participant: str, marker: sim_pb2.StepDone) -> None:
        self._events.put((RuntimeEvent.DONE, (participant, marker.step, marker.next_step, dict(marker.sequences))))

    def _on_liveliness(self, key: str, alive: bool) -> None:
        parts = key.split("/")
        if len(parts) == 4:
            self._events.put((RuntimeEvent.ALIVE, (participant_name(parts[1], parts[3]), alive)))

    # ----- followers ------------------------------------------------------------------------
    def _follow(self) -> None:
        while not self._stop.is_set():
            if self._clock_mode is ClockMode.WALL:
                timeout = min(self._triggers.seconds_until_next(self._clock.now_s()), 0.1)
            else:
                timeout = 0.1
            event = self.next_event(timeout)
            if event is not None:
                self._handle_follower_event(*event)
                # What was queued behind it first: the barrier is asked once per burst, not per message, and a
                # flood arriving meanwhile still leaves the triggers their turn.
                for _ in range(self._events.qsize()):
                    self._handle_follower_event(*self._events.get_nowait())
            self.run_what_is_due()

    def handle_events(self, events: list[tuple[RuntimeEvent, object]]) -> None:
        for kind, payload in events:
            self._handle_follower_event(kind, payload)

    @property
    def steps_pending(self) -> bool:
        """Whether run_what_is_due has anything to look at: lockstep clocks not yet handled (wall-clock triggers
        are always worth a look)."""
        return self._clock_mode is ClockMode.WALL or bool(self._pending_clocks)

    def run_what_is_due(self) -> None:
        """On the wall clock the triggers that are due; in simulated time the steps the barrier releases."""
        if self._clock_mode is ClockMode.WALL:
            self._triggers.run_due(self._clock.now_s())
        else:
            self._run_ready_steps()

    def _handle_follower_event(self, kind: RuntimeEvent, payload) -> None:
        if kind is RuntimeEvent.DATA:
            self.note_received(payload)
            if self._clock_mode is ClockMode.SIM and self._lockstep is not False:
                # Lockstep (or not known yet): handled in step order, never in arrival order.
                self._dispatcher.add(payload)
            else:
                self.dispatch(payload)
        elif kind is RuntimeEvent.CLOCK:
            self._clock_subscription.check_step(payload.step_s)
            self._lockstep = payload.lockstep
            if payload.lockstep:
                self._queue_clock(payload)
            else:
                self._clock.set(payload.time_s)
                self._track_participants(payload.participants)
                for envelope in self._dispatcher.eligible(payload.time_s):
                    self.dispatch(envelope)
                self._triggers.run_due(payload.time_s)
        elif kind is RuntimeEvent.DONE:
            self._join.on_marker(*payload)
        elif kind is RuntimeEvent.ALIVE:
            for handler in self._liveliness_handlers:
                handler(*payload)
        elif kind is RuntimeEvent.CALL:
            self.call(payload)

    def _track_participants(self, participants) -> None:
        for participant, alive in self._participant_tracker.update(participants):
            for handler in self._liveliness_handlers:
                handler(participant, alive)

    def call(self, function: Callable[[], None]) -> None:
        """Runs a function handed over by call_soon, on this service's worker."""
        try:
            function()
        except Exception:  # an input callback must not take the service down
            self.service.count("handler_errors")
            self.log.exception("call_soon function failed")

    def _queue_clock(self, clock: sim_pb2.SimClock) -> None:
        started = self._join.started
        joining = self._join.on_clock(clock.step, frozenset(clock.participants), clock.sequences)
        if not started and self._join.joined_step > 0:
            self._start_mid_run(clock)
            return
        if joining:
            self._resend_last_marker()
            for participant in joining:
                self._barrier.mark_done(participant, clock.step)  # it has nothing before its first step
        if clock.step <= self._last_step:
            return
        # Few of the simulator's topics are ours: look those up rather than walk the whole protobuf map.
        counted = clock.sequences
        # Those joining take part from the next step on.
        released = _ReleasedStep(clock.step, clock.time_s, clock.step_s, frozenset(clock.participants) - joining,
                                 {key: counted[key] for key in self._barrier.subscribed if key in counted})
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
        self._last_step = clock.step
        self._clock.set(clock.time_s)
        self._triggers.start_at(start_s)
        self._dispatcher.start_at(start_s)
        self.log.info("joined the run at step %d (%.3f s)", clock.step + 1, start_s)

    def _resend_last_marker(self) -> None:
        if self._last_marker is not None:
            for topic in self._stepped_topics:
                self.bus.put_if_subscribed(self.bus.layout.step_done(self.vehicle_id, topic), self._last_marker)

    def _run_ready_steps(self) -> None:
        while self._pending_clocks:
            released = self._pending_clocks[0]
            self._step_s = released.step_s
            if not self._triggers.any_due(released.time_s):
                self._pending_clocks.popleft()  # idle step: our last marker already covers it
                continue
            step, participants = released.step, released.participants
            if self._barrier.waits(step, participants) or not self._barrier.holds(released.sequences):
                if not self._gave_up_waiting_for_messages(step, participants):
                    return
            self._blocked_since = None
            self._pending_clocks.popleft()
            self._clock.set(released.time_s)
            self._track_participants(released.participants)
            self.run_lockstep_step(released.step, released.time_s)

    def run_lockstep_step(self, step: int, time_s: float) -> None:
        """Handles a released step, then sends what it published together with its step marker."""
        self._step_outbox = []
        self.run_step(step, time_s)
        self.publish_step_done(step)

    def _gave_up_waiting_for_messages(self, step: int, participants: set[str]) -> bool:
        """True when every step marker is in and only counted messages are missing, for MESSAGE_WAIT_LIMIT_S.

        A message lost on the way would otherwise hold the whole run forever; going on costs that one
        message (counted and logged), as it would on the vehicle.
        """
        now = time.monotonic()
        if self._blocked_since is None or self._blocked_since[0] != step:
            self._blocked_since = (step, now)
            return False
        still_waiting_for_markers = self._barrier.missing(step, participants, markers_only=True)
        if still_waiting_for_markers and now - max(self._blocked_since[1], self._stall_warned_at) > STALL_WARNING_S:
            self._stall_warned_at = now  # as the simulator warns: says who holds a stuck run
            self.log.warning("step %d still waits for %s", step, ", ".join(still_waiting_for_markers))
        if still_waiting_for_markers or now - self._blocked_since[1] < MESSAGE_WAIT_LIMIT_S:
            return False
        self.service.count(MESSAGES_GIVEN_UP_COUNTER)
        self.log.warning("step %d: gave up waiting for messages counted by %s", step,
                         ", ".join(self._barrier.missing(step, participants)) or "the simulator's clock")
        return True

    # ----- shared by followers and the master -----------------------------------------------
    def queued_events(self) -> int:
        return self._events.qsize()

    def next_event(self, timeout_s: float):
        try:
            return self._events.get(timeout=max(timeout_s, 0.0))
        except queue.Empty:
            return None

    def run_step(self, step: int, time_s: float) -> None:
        self._clock.set(time_s)
        for envelope in self._dispatcher.eligible(time_s):
            self.dispatch(envelope)
        self._triggers.run_due(time_s)
        self._last_step = step

    def publish_step_done(self, step: int) -> None:
        """Sends the step's messages and tells every subscriber of each stepped topic that the step is done.

        The marker rides as the attachment of the step's last message on each topic, so a step costs no
        extra message on the topics it used; a topic left quiet gets the marker on its own @step key.
        """
        marker = sim_pb2.StepDone(step=step, service=self._service_name, next_step=self._next_active_step(step),
                                  sequences=self._sequence.last)
        marker.header.sent_time_s = self._clock.now_s()
        marker.header.vehicle_id = self.vehicle_id
        marker.header.sender = self._service_name
        attachment = marker.SerializeToString()
        self._last_marker = marker
        outbox, self._step_outbox = self._step_outbox or [], None
        last_of_topic = {(vehicle_id, topic): index for index, (vehicle_id, topic, _) in enumerate(outbox)}
        for index, (vehicle_id, topic, message) in enumerate(outbox):
            carries_marker = (vehicle_id == self.vehicle_id and topic in self._stepped_topics
                              and last_of_topic[(vehicle_id, topic)] == index)
            self.bus.publish(vehicle_id, topic, message, attachment=attachment if carries_marker else None)
        sent = {topic for vehicle_id, topic, _ in outbox if vehicle_id == self.vehicle_id}
        for topic in self._stepped_topics:
            if topic not in sent:
                self.bus.put_if_subscribed(self.bus.layout.step_done(self.vehicle_id, topic), marker)

    def publish_clock(self, clock: sim_pb2.SimClock, followers_key: str) -> None:
        """The clock master's clock: numbered as world/clock and sent to the followers on `followers_key`
        (KeyLayout.clock_step or clock_to_all), and on world/clock itself for whoever records or shows it."""
        self._sequence.stamp(clock, WORLD_ID, "clock", self._clock.now_s(), None)
        self.bus.put(followers_key, clock)
        self.bus.put_if_subscribed(self.bus.layout.topic(WORLD_ID, "clock"), clock)

    def note_received(self, envelope: Envelope) -> None:
        self._barrier.mark_received(f"{envelope.vehicle_id}/{envelope.topic}", envelope.message.header.sequence)

    @property
    def published_sequences(self) -> dict[str, int]:
        return dict(self._sequence.last)

    def _next_active_step(self, step: int) -> int:
        next_due = self._triggers.next_due_s()
        if next_due is None or self._step_s <= 0:
            return step + 1
        return max(step + 1, math.ceil(next_due / self._step_s - TIME_EPSILON_S * 1e3))

    def _on_trigger_error(self, trigger, error: Exception) -> None:
        """Counted every time; the traceback is logged the first time and then every so often, not at 50 Hz."""
        self.service.count("handler_errors")
        name = getattr(trigger.handler, "__qualname__", repr(trigger.handler))
        failures = self._trigger_failures[name] = self._trigger_failures.get(name, 0) + 1
        if failures == 1 or failures % TRIGGER_FAILURE_LOG_EVERY == 0:
            self.log.error("periodic %s failed (%d times)", name, failures, exc_info=error)

    def _on_trigger_overrun(self, trigger, missed: int) -> None:
        """Logged the first time a trigger misses periods and then every so often; counted in diagnostics."""
        if trigger.overruns == missed or trigger.overruns // TRIGGER_FAILURE_LOG_EVERY > \
                (trigger.overruns - missed) // TRIGGER_FAILURE_LOG_EVERY:
            self.log.warning("periodic %s ran late: %d period(s) of %.3f s missed (%d so far)", trigger.name, missed,
                             trigger.period_s, trigger.overruns)

    def dispatch(self, envelope: Envelope) -> None:
        for source, handler in self._handlers.get(envelope.topic, ()):
            if source not in ("*", envelope.vehicle_id):
                continue
            try:
                handler(envelope)
            except Exception:  # a bad message must not take the service down
                self.service.count("handler_errors")
                self.log.exception("handler for %s failed", envelope.topic)

    @property
    def dispatcher(self) -> StepDispatcher:
        return self._dispatcher

    @property
    def barrier(self) -> StepBarrier:
        return self._barrier

    @property
    def clock_master(self) -> ClockMaster | None:
        return self._master

    @property
    def stopping(self) -> bool:
        return self._stop.is_set()

    def _publish_diagnostics(self, now_s: float) -> None:
        message = diagnostics_pb2.Diagnostics(level=diagnostics_pb2.HEALTH_LEVEL_OK)
        for name, value in self.service.counters.items():
            message.counters[name] = value
        message.counters["bus_decode_errors"] = self.bus.decode_errors
        message.counters["bus_callback_errors"] = self.bus.callback_errors
        for name, overruns in self._triggers.overruns().items():
            message.counters[f"overruns_{name}"] = overruns
        # CPU the service's own worker thread has used (handlers and triggers): where a run's time goes.
        message.counters["worker_cpu_s"] = self.own_cpu_s
        self.publish(f"diagnostics/{self._service_name}", message)

    def _service_info(self) -> Message:
        from coopdrive.v1 import diagnostics_pb2 as diag

        return diag.ServiceInfo(
            service=self._service_name, vehicle_id=self.vehicle_id,
            state="stopping" if self._stop.is_set() else "running",
            config_json=self.service.config.model_dump_json(),
            uptime_s=time.monotonic() - self._started_monotonic, pid=os.getpid())
