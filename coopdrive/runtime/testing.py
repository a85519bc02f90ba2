"""MemoryContext: a whole ServiceContext in memory, for tests and for replay (ReplayContext builds on it).

A test constructs a service with one, starts it, then plays the bus: deliver() hands a message to the
service's handlers, advance_to() moves the clock and runs the time triggers due, set_alive() reports a
participant's liveliness, and messages(topic) reads back what the service published.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections import defaultdict
from typing import Callable

from google.protobuf.message import Message

from coopdrive.bus import Envelope, KeyLayout
from coopdrive.runtime.clock import SimulationClock
from coopdrive.runtime.service import SequenceCounter
from coopdrive.runtime.timers import TriggerSet

# How long pump() waits for a call_soon from another thread (a socket's or serial port's reader).
PUMP_TIMEOUT_S = 2.0


class MemoryContext:
    """The ServiceContext protocol without a bus: what is published is kept in order, stamped as the live
    runtime stamps it; time is a SimulationClock unless another clock (e.g. WallClock) is given.

    call_soon runs the function at once, on the caller's thread, unless queue_calls: then the functions wait
    for pump(), which runs them on the test's thread as the service's worker would.
    """

    def __init__(self, vehicle_id: str = "ego", service_name: str = "test", *, log: logging.Logger | None = None,
                 clock=None, opens_hardware: bool = False, queue_calls: bool = False) -> None:
        self.vehicle_id = vehicle_id
        self.service_name = service_name
        self.log = log or logging.getLogger(f"coopdrive.memory.{service_name}")
        self.clock = clock if clock is not None else SimulationClock()
        self.opens_hardware = opens_hardware
        self.bus_mode = "none"  # no bus at all
        self.layout = KeyLayout()
        self.triggers = TriggerSet()
        self.handlers: dict[str, list[tuple[str, Callable[[Envelope], None]]]] = defaultdict(list)
        self.liveliness_handlers: list[Callable[[str, bool], None]] = []
        self.outputs: list[tuple[str, Message]] = []  # (key, message): what the bus would have carried
        self.stop_reasons: list[str] = []
        self._sequence = SequenceCounter(service_name)
        self._calls: queue.Queue | None = queue.Queue() if queue_calls else None
        self._lock = threading.Lock()  # a reader thread may publish through call_soon while the test reads

    # ----- ServiceContext -------------------------------------------------------------------
    def now_s(self) -> float:
        return self.clock.now_s()

    def subscribe(self, topic: str, handler: Callable[[Envelope], None], vehicle_id: str | None = None) -> None:
        self.handlers[topic].append((vehicle_id or self.vehicle_id, handler))

    def publish(self, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        self.publish_for(self.vehicle_id, topic, message, sample_time_s)

    def publish_for(self, vehicle_id: str, topic: str, message: Message, sample_time_s: float | None = None) -> None:
        with self._lock:
            self._sequence.stamp(message, vehicle_id, topic, self.clock.now_s(), sample_time_s)
            self.outputs.append((self.layout.topic(vehicle_id, topic), message))

    def every(self, period_s: float, handler: Callable[[float], None]) -> None:
        self.triggers.add(period_s, handler)

    def watch_liveliness(self, handler: Callable[[str, bool], None]) -> None:
        self.liveliness_handlers.append(handler)

    def call_soon(self, function: Callable[[], None]) -> None:
        if self._calls is None:
            function()
        else:
            self._calls.put(function)

    def request_stop(self, reason: str) -> None:
        self.stop_reasons.append(reason)
        self.log.info("service asked to stop: %s", reason)

    # ----- playing the bus ------------------------------------------------------------------
    def dispatch(self, envelope: Envelope) -> None:
        """Hands a received message to every handler subscribed to its topic from its vehicle (or from any)."""
        for source, handler in self.handlers.get(envelope.topic, ()):
            if source in ("*", envelope.vehicle_id):
                handler(envelope)

    def deliver(self, topic: str, message: Message, vehicle_id: str | None = None) -> None:
        """dispatch() of a message from vehicle_id (this vehicle by default); one without a sent time gets
        the clock's now, as every sender stamps what it publishes."""
        header = getattr(message, "header", None)
        if header is not None and not header.sent_time_s:
            header.sent_time_s = self.clock.now_s()
        self.dispatch(Envelope(vehicle_id or self.vehicle_id, topic, message))

    def advance_to(self, time_s: float) -> None:
        """Sets the clock (a SimulationClock) and runs the time triggers due by then."""
        self.clock.set(time_s)
        self.triggers.run_due(time_s)

    def set_alive(self, participant: str, alive: bool) -> None:
        """Liveliness of "<vehicle>/<service>" as the bus would report it."""
        for handler in self.liveliness_handlers:
            handler(participant, alive)

    def pump(self, calls: int, timeout_s: float = PUMP_TIMEOUT_S) -> None:
        """Runs the next `calls` functions queued by call_soon, waiting up to timeout_s for each."""
        for _ in range(calls):
            self._calls.get(timeout=timeout_s)()

    # ----- reading back ---------------------------------------------------------------------
    def messages(self, topic: str, vehicle_id: str | None = None) -> list[Message]:
        """What was published on topic for vehicle_id (this vehicle by default), in order."""
        key = self.layout.topic(vehicle_id or self.vehicle_id, topic)
        with self._lock:
            return [message for name, message in self.outputs if name == key]

    @property
    def published(self) -> list[tuple[str, Message]]:
        """(topic, message) of everything published for this vehicle, in order."""
        prefix = self.layout.topic(self.vehicle_id, "")
        with self._lock:
            return [(key[len(prefix):], message) for key, message in self.outputs if key.startswith(prefix)]

    def subscriptions(self) -> set[tuple[str, str]]:
        """(source vehicle or "*", topic) of every subscription."""
        return {(source, topic) for topic, handlers in self.handlers.items() for source, _ in handlers}

    def trigger_periods_s(self) -> dict[str, float]:
        """The period of each time trigger, by its handler's name."""
        return {trigger.name: trigger.period_s for trigger in self.triggers}
