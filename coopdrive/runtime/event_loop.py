"""EventLoop: a service's queue of events and the one switch that hands each to the part of the runtime that owns
its kind. Zenoh callbacks, input threads and call_soon only put events here; the worker takes them out.

The follower (follower.py) and the clock master (master.py) each say what an event means to them as an EventRole;
the switch, the wait for the next event and the handling of a burst are the same for both."""

from __future__ import annotations

import queue
from typing import Callable, Protocol

from coopdrive.bus import Envelope
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.v1 import sim_pb2


class EventInbox(Protocol):
    """Where a service's events are put: its own queue, or its entry in a SharedWorker's."""

    def put(self, item) -> None: ...


class EventRole(Protocol):
    """What the events of a service's worker mean to its role (a clock follower or the clock master)."""

    def on_data(self, envelope: Envelope) -> None: ...

    def on_clock(self, clock: sim_pb2.SimClock) -> None: ...

    def on_step_done(self, participant: str, step: int, next_step: int, sequences: dict[str, int]) -> None: ...

    def on_alive(self, participant: str, alive: bool) -> None: ...


class EventLoop:
    def __init__(self, inbox: EventInbox | None, call: Callable[[Callable[[], None]], None]):
        """`inbox`: where events go when a SharedWorker takes them instead of this loop's own queue.
        `call`: runs a function handed over by call_soon (the context's, which keeps a failure from spreading)."""
        self.inbox: EventInbox = inbox if inbox is not None else queue.SimpleQueue()
        self._call = call

    def put(self, kind: RuntimeEvent, payload) -> None:
        self.inbox.put((kind, payload))

    def queued_events(self) -> int:
        return self.inbox.qsize()

    def next_event(self, timeout_s: float):
        try:
            return self.inbox.get(timeout=max(timeout_s, 0.0))
        except queue.Empty:
            return None

    def handle(self, event, role: EventRole) -> None:
        """The one event switch: each kind to what `role` does with it (STOP only wakes the loop)."""
        if event is None:
            return
        kind, payload = event
        if kind is RuntimeEvent.DATA:
            role.on_data(payload)
        elif kind is RuntimeEvent.CLOCK:
            role.on_clock(payload)
        elif kind is RuntimeEvent.DONE:
            role.on_step_done(*payload)
        elif kind is RuntimeEvent.ALIVE:
            role.on_alive(*payload)
        elif kind is RuntimeEvent.CALL:
            self._call(payload)

    def handle_burst(self, timeout_s: float, role: EventRole) -> bool:
        """Waits up to `timeout_s` for an event, handles it and then what queued behind it: the barrier is asked once
        per burst, not once per message, and a flood arriving meanwhile still leaves the triggers their turn. True
        when an event came."""
        event = self.next_event(timeout_s)
        if event is None:
            return False
        self.handle(event, role)
        for _ in range(self.queued_events()):
            self.handle(self.inbox.get_nowait(), role)
        return True
