"""ServiceGroup: several services in one process sharing one Zenoh session.

On the vehicle every service is its own process; in simulation a vehicle's whole stack can run as one
process (`coopdrive group`), which saves a Python interpreter per service and lets the vehicle's services
reach each other through the shared session without a socket. Each service keeps its own runner, so its
life cycle, triggers, liveliness token and lockstep barrier are exactly those of a lone process.

In simulated time one SharedWorker thread handles every service's events (see shared_worker.py); on the wall
clock each service has its own worker thread, so that a long handler in one delays another no more than the
interpreter's lock would. Setting COOPDRIVE_GROUP_THREAD_PER_SERVICE=1 gives every service its own thread in
simulated time too, as before the shared worker: the benchmarks' baseline (docs/performance.md).

The simulator, which owns the clock, may join a group too (`coopdrive run --processes one`): its runner keeps a
thread of its own, which steps the world and waits for the services' step markers, as in a process of its own.
"""

from __future__ import annotations

import logging
import os
import signal
import threading
from dataclasses import dataclass

from coopdrive.bus import Bus, BusConfig
from coopdrive.runtime.master import ClockMaster
from coopdrive.runtime.runner import ClockMode, ServiceRunner
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.runtime.shared_worker import SharedWorker
from coopdrive.runtime.signal_wait import join_hearing_signals

log = logging.getLogger("coopdrive.group")

THREAD_PER_SERVICE_VARIABLE = "COOPDRIVE_GROUP_THREAD_PER_SERVICE"


@dataclass
class GroupMember:
    service_cls: type[Service]
    config: ServiceConfig
    vehicle_id: str

    @property
    def participant(self) -> str:
        return f"{self.vehicle_id}/{self.service_cls.name}"


class ServiceGroup:
    def __init__(self, members: list[GroupMember], bus_config: BusConfig, clock_mode: ClockMode = ClockMode.WALL,
                 clock_step_s: float | None = None):
        if not members:
            raise ValueError("a service group needs at least one service")
        self._bus = Bus(bus_config)
        self._members = members
        shared = clock_mode is ClockMode.SIM and os.environ.get(THREAD_PER_SERVICE_VARIABLE) != "1"
        followers = [member for member in members if not issubclass(member.service_cls, ClockMaster.Driven)]
        self.worker = SharedWorker(f"{members[0].vehicle_id}-group") if shared and followers else None
        self.runners = []
        # The members that run on a thread of their own: every member without a shared worker, else the clock's.
        self._own_threads: list[tuple[GroupMember, ServiceRunner]] = []
        for member in members:
            on_worker = self.worker is not None and member in followers
            runner = ServiceRunner(member.service_cls, member.config, member.vehicle_id, None, clock_mode,
                                   bus=self._bus.sharing(), clock_step_s=clock_step_s,
                                   inbox=self.worker.inbox() if on_worker else None)
            if on_worker:
                self.worker.add(member.participant, runner)
            else:
                self._own_threads.append((member, runner))
            self.runners.append(runner)
        self.failed: dict[str, str] = self.worker.failed if self.worker else {}
        # The clock's service stops after the others, as the world outlives a vehicle: they may still read what it
        # writes (a GNSS pty) in their last step.
        self._clock_runners = [runner for runner in self.runners if runner.clock_master is not None]
        self._signal: str | None = None
        self._followers_done = False

    def run(self) -> dict[str, str]:
        """Runs every service until SIGINT/SIGTERM or until all have stopped; returns participant -> stop reason."""
        reasons: dict[str, str] = self.worker.reasons if self.worker else {}
        threads = {runner: threading.Thread(target=self._run_one, args=(member, runner, reasons),
                                            name=member.participant) for member, runner in self._own_threads}
        followers = [thread for runner, thread in threads.items() if runner not in self._clock_runners]
        if self.worker:
            followers.append(threading.Thread(target=self.worker.run, name=f"{self._members[0].vehicle_id}/group"))
        clocks = [threads[runner] for runner in self._clock_runners]
        previous = {}
        if threading.current_thread() is threading.main_thread():
            previous = {s: signal.signal(s, lambda sig, _frame: self._on_signal(signal.Signals(sig).name))
                        for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            for thread in clocks + followers:
                thread.start()
            join_hearing_signals(followers)
            self._followers_done = True
            if self._signal is not None:
                self._signal_clocks()
            join_hearing_signals(clocks)
        finally:
            for signum, handler in previous.items():
                signal.signal(signum, handler)
            self._bus.close()
        return reasons

    def request_stop(self, reason: str) -> None:
        for runner in self.runners:
            runner.request_stop(reason)

    def _on_signal(self, name: str) -> None:
        """As each service's runner takes the signal in a process of its own; the clock's (which then ends its
        linger) once the others have stopped."""
        self._signal = name
        for runner in self.runners:
            if runner not in self._clock_runners:
                runner.on_signal(name)
        if self._followers_done:
            self._signal_clocks()

    def _signal_clocks(self) -> None:
        for runner in self._clock_runners:
            runner.on_signal(self._signal)

    def _run_one(self, member: GroupMember, runner: ServiceRunner, reasons: dict[str, str]) -> None:
        try:
            reasons[member.participant] = runner.run()
        except Exception as error:  # one service failing must not take its neighbours down
            log.exception("%s stopped with an error", member.participant)
            self.failed[member.participant] = f"{type(error).__name__}: {error}"
            reasons[member.participant] = self.failed[member.participant]
