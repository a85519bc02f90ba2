"""SharedWorker: one thread that handles the events of several services of one process, in simulated time.

The services of a process share one interpreter lock, so only one of them runs Python at a time anyway. On a
thread each, they traded that lock at every call into native code (each Zenoh put, each small numpy product) and
woke each other for every message one published to another; most of those wake-ups found the lock taken. One
thread takes every service's events from one queue, hands each to its service and then runs whatever steps the
lockstep barrier releases, so a message from one service to another in the process is a queue entry, not a
thread switch.

What a service does is unchanged: each keeps its own runner, dispatcher, barrier and triggers, and in lockstep the
order in which a service handles data is fixed by the step rule, not by arrival. On the wall clock a group keeps
a thread per service (see ServiceGroup), so that one service's long handler does not delay another's trigger.
"""

from __future__ import annotations

import logging
import queue
import time
from collections import defaultdict
from dataclasses import dataclass

from coopdrive.runtime.profiling import WorkerProfile
from coopdrive.runtime.runner import ServiceRunner

log = logging.getLogger("coopdrive.group")

# How long the worker waits for an event before it looks at its services' stop flags again.
IDLE_WAIT_S = 0.1


@dataclass(frozen=True)
class WorkerInbox:
    """A service's events as its producers (Zenoh callbacks, call_soon, request_stop) put them: tagged with the
    service's place in the worker and put on the worker's one queue."""

    index: int
    events: queue.SimpleQueue

    def put(self, item) -> None:
        self.events.put((self.index, item))


class SharedWorker:
    def __init__(self, name: str):
        self._name = name
        self._events: queue.SimpleQueue = queue.SimpleQueue()
        self._runners: list[ServiceRunner] = []
        self._participants: list[str] = []
        # participant -> the reason it stopped, or the error it failed with.
        self.reasons: dict[str, str] = {}
        self.failed: dict[str, str] = {}

    def inbox(self) -> WorkerInbox:
        """The inbox of the next service added."""
        return WorkerInbox(len(self._runners), self._events)

    def add(self, participant: str, runner: ServiceRunner) -> None:
        if runner.clock_master is not None:
            raise ValueError(f"{participant} owns the clock: it needs a thread of its own")
        self._runners.append(runner)
        self._participants.append(participant)
        runner.worker_cpu_s = 0.0

    def run(self) -> None:
        """Starts every service, handles their events until each has stopped, then stops them (in that order)."""
        active = [index for index in range(len(self._runners)) if self._guarded(index, ServiceRunner.begin)]
        with WorkerProfile.from_environment(self._name):
            while active:
                self._handle_queued(active)
                # A service that failed was asked to stop (see _guarded).
                active = [index for index in active if not self._runners[index].stopping]
                for index in active:
                    if self._runners[index].steps_pending:
                        self._guarded(index, ServiceRunner.run_what_is_due)
        for index, runner in enumerate(self._runners):
            self._guarded(index, ServiceRunner.end)
            self.reasons.setdefault(self._participants[index], runner.stop_reason)

    def _handle_queued(self, active: list[int]) -> None:
        """Waits for an event (at most IDLE_WAIT_S), then hands it and whatever queued behind it to their services:
        each service's in the order they came, one service after the other."""
        try:
            first = self._events.get(timeout=IDLE_WAIT_S)
        except queue.Empty:
            return
        burst: dict[int, list] = defaultdict(list)
        burst[first[0]].append(first[1])
        for _ in range(self._events.qsize()):
            index, event = self._events.get_nowait()
            burst[index].append(event)
        for index, events in burst.items():
            if index in active:
                self._guarded(index, ServiceRunner.handle_events, events)

    def _guarded(self, index: int, action, *args) -> bool:
        """Runs one service's part, charging its CPU to that service; an error stops that service only."""
        runner = self._runners[index]
        started = time.thread_time()
        try:
            action(runner, *args)
            return True
        except Exception as error:  # one service failing must not take its neighbours down
            participant = self._participants[index]
            log.exception("%s stopped with an error", participant)
            self.failed.setdefault(participant, f"{type(error).__name__}: {error}")
            self.reasons[participant] = self.failed[participant]
            runner.request_stop(self.failed[participant])
            return False
        finally:
            runner.worker_cpu_s += time.thread_time() - started
