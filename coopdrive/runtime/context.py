"""RunnerContext: what a running service sees of the runtime (runtime/service.py's ServiceContext) on a live bus:
its clock, its subscriptions and their handlers, publishing, periodic triggers, call_soon and stopping; and what
comes in off the bus for it, messages and the step markers they carry, queued for its worker."""

from __future__ import annotations

import logging
import threading
from collections import defaultdict
from typing import Callable

from google.protobuf.message import DecodeError, Message

from coopdrive.bus import Bus, Envelope
from coopdrive.bus.topics import topic_named
from coopdrive.runtime.clock_subscription import ClockSubscription
from coopdrive.runtime.event_loop import EventInbox, EventLoop
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.runtime.handler_ledger import HandlerLedger, handler_name
from coopdrive.runtime.pipeline import participant_name
from coopdrive.runtime.stepping import Stepper
from coopdrive.v1 import sim_pb2


class RunnerContext:
    opens_hardware = True

    def __init__(self, vehicle_id: str, log: logging.Logger, bus: Bus, clock, steps: Stepper,
                 ledger: HandlerLedger | None, inbox: EventInbox | None = None):
        """`inbox`: where this service's events go when a SharedWorker handles them instead of its own loop."""
        self.vehicle_id = vehicle_id
        self.log = log
        self.bus = bus
        self.bus_mode = bus.mode
        self._clock = clock
        self._steps = steps
        self._ledger = ledger
        self.events = EventLoop(inbox, self.call)
        self.clock_subscription: ClockSubscription | None = None
        # topic -> (source vehicle or "*", handler)
        self._handlers: dict[str, list[tuple[str, Callable[[Envelope], None]]]] = defaultdict(list)
        self.bus_subscriptions: set[tuple[str, str]] = set()
        self.liveliness_handlers: list[Callable[[str, bool], None]] = []
        self._stop = threading.Event()
        self._stop_reason = ""
        # Counts a failed handler; the runner sets it to its service's count once the service exists.
        self.count: Callable[[str], None] = lambda _name: None

    # ----- ServiceContext -------------------------------------------------------------------
    def now_s(self) -> float:
        return self._clock.now_s()

    def subscribe(self, topic: str, handler: Callable[[Envelope], None], vehicle_id: str | None = None) -> None:
        source = vehicle_id or self.vehicle_id
        spec = topic_named(topic)
        stepped = source != "*" and spec.stepped
        barrier = self._steps.barrier
        if stepped:
            barrier.depend_on(participant_name(source, spec.publisher))
        if (source, topic) not in self.bus_subscriptions:
            self.bus_subscriptions.add((source, topic))
            if stepped:
                barrier.subscribed.add(f"{source}/{topic}")
            self.bus.subscribe(source, topic, self.on_data)
        if self._ledger is not None:
            handler = self._ledger.timed("topic", topic, handler)
        self._handlers[topic].append((source, handler))

    def publish(self, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        self.publish_for(self.vehicle_id, topic, message, sample_time_s)

    def publish_for(self, vehicle_id: str, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        """Publishes under another vehicle's namespace (the simulator feeds every vehicle)."""
        self._steps.sequence.stamp(message, vehicle_id, topic, self._clock.now_s(), sample_time_s)
        self._steps.send(vehicle_id, topic, message)

    def every(self, period_s: float, handler: Callable[[float], None]) -> None:
        if self._ledger is not None:
            handler = self._ledger.timed("timer", handler_name(handler), handler)
        self._steps.triggers.add(period_s, handler)
        self.clock_subscription.trigger_added()

    def watch_liveliness(self, handler: Callable[[str, bool], None]) -> None:
        self.liveliness_handlers.append(handler)

    def call_soon(self, function: Callable[[], None]) -> None:
        if self._ledger is not None:
            function = self._ledger.timed("call", handler_name(function), function)
        self.events.put(RuntimeEvent.CALL, function)

    def request_stop(self, reason: str) -> None:
        self._stop_reason = reason
        self._stop.set()
        self.events.put(RuntimeEvent.STOP, None)

    # ----- the runtime's side ---------------------------------------------------------------
    @property
    def stop_reason(self) -> str:
        return self._stop_reason

    @property
    def stopping(self) -> bool:
        return self._stop.is_set()

    def on_data(self, envelope: Envelope) -> None:
        """A subscribed message off the bus (on Zenoh's thread), and the step marker it carries: queued for the
        worker."""
        self.events.put(RuntimeEvent.DATA, envelope)
        if envelope.attachment is None:
            return
        participant = self.awaited_publisher(envelope.vehicle_id, envelope.topic)
        if participant is None:
            return
        marker = sim_pb2.StepDone()
        try:
            marker.ParseFromString(envelope.attachment)
        except DecodeError as error:
            self.count("bad_step_markers")
            self.log.warning("dropped a malformed step marker on %s/%s: %s", envelope.vehicle_id, envelope.topic, error)
            return
        self.on_step_marker(participant, marker)

    def awaited_publisher(self, vehicle_id: str, topic: str) -> str | None:
        """The participant whose step markers this service waits for on `topic` of `vehicle_id`, if any."""
        spec = topic_named(topic)
        participant = participant_name(vehicle_id, spec.publisher)
        return participant if spec.stepped and self._steps.barrier.depends_on(participant) else None

    def on_step_marker(self, participant: str, marker: sim_pb2.StepDone) -> None:
        self.events.put(RuntimeEvent.DONE, (participant, marker.step, marker.next_step, dict(marker.sequences)))

    def on_liveliness(self, key: str, alive: bool) -> None:
        parts = key.split("/")
        if len(parts) == 4:
            self.events.put(RuntimeEvent.ALIVE, (participant_name(parts[1], parts[3]), alive))

    def dispatch(self, envelope: Envelope) -> None:
        for source, handler in self._handlers.get(envelope.topic, ()):
            if source not in ("*", envelope.vehicle_id):
                continue
            try:
                handler(envelope)
            except Exception:  # a bad message must not take the service down
                self.count("handler_errors")
                self.log.exception("handler for %s failed", envelope.topic)

    def call(self, function: Callable[[], None]) -> None:
        """Runs a function handed over by call_soon, on this service's worker."""
        try:
            function()
        except Exception:  # an input callback must not take the service down
            self.count("handler_errors")
            self.log.exception("call_soon function failed")
