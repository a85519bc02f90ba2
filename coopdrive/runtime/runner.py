"""ServiceRunner: runs one Service on a live bus, with wall, simulated or lockstep time: its life cycle.

It builds the runtime's parts and hands the service its context; each part has one role:

- context.py (RunnerContext): what the service sees (subscribe, publish, every, call_soon, ...) and what comes in;
- event_loop.py (EventLoop): the queue of events and the one switch over them; Zenoh callbacks only enqueue and a
  single worker handles every message and time trigger, so a service's code never runs on two threads at once;
- follower.py (ClockFollower): the worker loop of a service on the wall clock or following the simulator's clock;
- master.py (ClockMaster): the worker loop of the one service that owns simulated time;
- stepping.py (Stepper) and step_wait.py (StepWait): a lockstep step, and how long it may wait;
- runner_diagnostics.py (RunnerDiagnostics): counters, service info, failing and late triggers.
"""

from __future__ import annotations

import logging
import signal
import threading
import time

from coopdrive.bus import Bus, BusConfig
from coopdrive.runtime.clock import SimulationClock, WallClock
from coopdrive.runtime.clock_subscription import ClockSubscription
from coopdrive.runtime.context import RunnerContext
from coopdrive.runtime.event_loop import EventInbox
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.runtime.follower import ClockFollower, ClockMode
from coopdrive.runtime.handler_ledger import HandlerLedger
from coopdrive.runtime.launcher_watch import launched_by_a_run
from coopdrive.runtime.master import ClockMaster
from coopdrive.runtime.profiling import WorkerProfile
from coopdrive.runtime.runner_diagnostics import DIAGNOSTICS_PERIOD_S, RunnerDiagnostics
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.runtime.signal_wait import wait_hearing_signals
from coopdrive.runtime.step_wait import StepWait
from coopdrive.runtime.stepping import Stepper
from coopdrive.runtime.timers import TriggerSet

# A finished clock master waits this long at most for its launcher to stop it (see _linger_for_the_launcher).
MASTER_LINGER_S = 60.0

__all__ = ["ClockMode", "EventInbox", "ServiceRunner"]


class ServiceRunner:
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
        clock = WallClock() if clock_mode is ClockMode.WALL else SimulationClock()
        # CPU of this service's handling, kept by a SharedWorker; None: the worker thread's own CPU time.
        self.worker_cpu_s: float | None = None
        self._ledger = HandlerLedger.from_environment(f"{vehicle_id}-{service_cls.name}")
        # Set by SIGINT/SIGTERM: the process is asked to end, by its launcher or its user.
        self._signalled = threading.Event()
        self.bus = bus if bus is not None else Bus(bus_config)
        self._diagnostics = RunnerDiagnostics(service_cls.name, vehicle_id, self.log, self.bus)
        triggers = TriggerSet(on_error=self._diagnostics.on_trigger_error,
                              on_overrun=self._diagnostics.on_trigger_overrun)
        self.steps = Stepper(service_cls.name, vehicle_id, self.bus, clock, triggers, self._dispatch)
        self.context = RunnerContext(vehicle_id, self.log, self.bus, clock, self.steps, self._ledger, inbox)
        self.context.clock_subscription = ClockSubscription(
            self.bus, lambda sim_clock: self.context.events.put(RuntimeEvent.CLOCK, sim_clock), clock_step_s)
        self.service = service_cls(config, self.context)
        self.context.count = self.service.count
        self._diagnostics.service = self.service
        self._diagnostics.stopping = lambda: self.context.stopping
        self._diagnostics.own_cpu_s = lambda: self.own_cpu_s
        step_wait = StepWait(self.steps.barrier, self.log, self.service.count)
        self._master = ClockMaster(self.service, self.context, self.steps, step_wait) \
            if isinstance(self.service, ClockMaster.Driven) else None
        self.follower = ClockFollower(self.context, self.steps, clock_mode, step_wait)

    def _dispatch(self, envelope) -> None:
        self.context.dispatch(envelope)

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
                    self.follower.run()
        finally:
            self.end()
        return self.stop_reason

    def begin(self) -> None:
        """Starts the service and declares what the runtime needs on the bus; the last before events flow."""
        self.service.start()
        self.steps.triggers.add(DIAGNOSTICS_PERIOD_S, self._publish_diagnostics)
        self._declare_runtime_entities()

    def end(self) -> None:
        try:
            self.service.stop()
        finally:
            self.bus.close()
            if self._ledger is not None:
                self._ledger.write(self.own_cpu_s)

    def request_stop(self, reason: str) -> None:
        self.context.request_stop(reason)

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
        context = self.context
        if self._clock_mode is ClockMode.SIM and self._master is None:
            context.clock_subscription.declare(self.steps.triggers.periods_s())
        for source, topic in sorted(context.bus_subscriptions):
            participant = context.awaited_publisher(source, topic)
            if participant is not None:
                self.bus.subscribe_key(layout.step_done(source, topic),
                                       lambda _key, marker, participant=participant:
                                       context.on_step_marker(participant, marker))
        if self._master is not None or (context.liveliness_handlers and self._clock_mode is ClockMode.WALL):
            # In simulation, followers learn liveliness from the clock (see participants.py).
            self.bus.watch_liveliness(layout.all_liveliness(), context.on_liveliness)
        self.bus.declare_queryable(layout.service_info(self.vehicle_id, self._service_name),
                                   self._diagnostics.service_info)
        # Last: the token tells the others that every subscription above is in place.
        self.bus.declare_token(layout.liveliness(self.vehicle_id, self._service_name))

    def _publish_diagnostics(self, _now_s: float) -> None:
        self.context.publish(f"diagnostics/{self._service_name}", self._diagnostics.message(self.steps.triggers))

    # ----- what a SharedWorker, the launcher and tests ask of a runner ------------------------
    @property
    def own_cpu_s(self) -> float:
        """The CPU this service's handling has used: its share of a SharedWorker, or its own thread's."""
        return time.thread_time() if self.worker_cpu_s is None else self.worker_cpu_s

    @property
    def stop_reason(self) -> str:
        return self.context.stop_reason

    @property
    def stopping(self) -> bool:
        return self.context.stopping

    def call_soon(self, function) -> None:
        self.context.call_soon(function)

    def handle_events(self, events: list[tuple[RuntimeEvent, object]]) -> None:
        self.follower.handle_events(events)

    @property
    def steps_pending(self) -> bool:
        return self.follower.steps_pending

    def run_what_is_due(self) -> None:
        self.follower.run_what_is_due()

    def run_lockstep_step(self, step: int, time_s: float) -> None:
        self.steps.run_lockstep_step(step, time_s)

    @property
    def clock_master(self) -> ClockMaster | None:
        return self._master
