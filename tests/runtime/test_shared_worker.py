"""In simulated time one thread handles every service of a group; on the wall clock they run side by side."""

import threading
import time

import pytest

from coopdrive.bus import BusConfig
from coopdrive.runtime.group import THREAD_PER_SERVICE_VARIABLE, GroupMember, ServiceGroup
from coopdrive.runtime.runner import ClockMode
from coopdrive.runtime.service import Service

PERIOD_S = 0.02
# Longer than the period, so that two services whose handlers may overlap do overlap.
HANDLER_S = 0.03
RUN_S = 0.6
DEADLINE_S = 5.0
BUSY_S = 0.1


class Planner(Service):
    """Keeps its worker busy for HANDLER_S on every tick (sleeping, so without holding the interpreter lock) and
    records on which thread and when each call of its own ran."""

    name = "planner"

    def __init__(self, config, ctx):
        super().__init__(config, ctx)
        self.busy: list[tuple[float, float]] = []
        self.threads: set[int] = set()

    def start(self) -> None:
        self.ctx.every(PERIOD_S, self.on_tick)

    def on_tick(self, _now_s: float) -> None:
        self.sleep_busy()

    def sleep_busy(self) -> None:
        started = time.monotonic()
        self.threads.add(threading.get_ident())
        time.sleep(HANDLER_S)
        self.busy.append((started, time.monotonic()))

    def spin_busy(self) -> None:
        end = time.thread_time() + BUSY_S
        while time.thread_time() < end:
            pass


class Control(Planner):
    name = "control"


class FailingScene(Planner):
    name = "scene"

    def start(self) -> None:
        raise RuntimeError("no map")


def overlaps(runners) -> int:
    """How many pairs of busy intervals of two services overlap."""
    first, second = (runner.service.busy for runner in runners)
    return sum(1 for a0, a1 in first for b0, b1 in second if a0 < b1 and b0 < a1)


def started_group(clock_mode: ClockMode, *classes) -> tuple[ServiceGroup, threading.Thread]:
    group = ServiceGroup([GroupMember(cls, cls.Config(), "ego") for cls in classes], BusConfig(), clock_mode)
    worker = threading.Thread(target=group.run)
    worker.start()
    return group, worker


def stopped(group: ServiceGroup, worker: threading.Thread) -> None:
    group.request_stop("test over")
    worker.join(DEADLINE_S)
    assert not worker.is_alive()


def wait_until(condition) -> None:
    end = time.monotonic() + DEADLINE_S
    while not condition():
        assert time.monotonic() < end, "timed out"
        time.sleep(0.01)


def test_on_the_wall_clock_the_services_of_a_group_run_side_by_side_on_their_own_threads():
    group, worker = started_group(ClockMode.WALL, Planner, Control)
    time.sleep(RUN_S)
    stopped(group, worker)
    planner, control = (runner.service for runner in group.runners)
    assert planner.threads.isdisjoint(control.threads)
    assert overlaps(group.runners) > 0


def after_calls(calls_each: int) -> ServiceGroup:
    """A simulated-time group of Planner and Control, stopped after each has handled calls_each sleep_busy calls."""
    group, worker = started_group(ClockMode.SIM, Planner, Control)
    try:
        for _ in range(calls_each):
            for runner in group.runners:
                runner.call_soon(runner.service.sleep_busy)
        wait_until(lambda: all(len(runner.service.busy) == calls_each for runner in group.runners))
    finally:
        stopped(group, worker)
    return group


def test_in_simulated_time_one_thread_handles_every_service_one_call_at_a_time():
    group = after_calls(5)
    planner, control = (runner.service for runner in group.runners)
    assert len(planner.threads | control.threads) == 1
    assert threading.get_ident() not in planner.threads
    assert overlaps(group.runners) == 0


def test_the_benchmarks_baseline_gives_each_service_of_a_group_in_simulated_time_its_own_thread(monkeypatch):
    monkeypatch.setenv(THREAD_PER_SERVICE_VARIABLE, "1")
    group = after_calls(1)
    planner, control = (runner.service for runner in group.runners)
    assert group.worker is None
    assert planner.threads.isdisjoint(control.threads)


def test_each_service_s_worker_cpu_is_what_its_own_handling_used():
    group, worker = started_group(ClockMode.SIM, Planner, Control)
    planner_runner, control_runner = group.runners
    try:
        planner_runner.call_soon(planner_runner.service.spin_busy)
        wait_until(lambda: planner_runner.worker_cpu_s >= BUSY_S)
    finally:
        stopped(group, worker)
    assert control_runner.worker_cpu_s < BUSY_S / 2


def test_a_service_that_fails_to_start_stops_alone_and_the_others_go_on():
    group, worker = started_group(ClockMode.SIM, FailingScene, Control)
    control_runner = group.runners[1]
    try:
        control_runner.call_soon(control_runner.service.sleep_busy)
        wait_until(lambda: len(control_runner.service.busy) == 1)
        assert group.failed == {"ego/scene": "RuntimeError: no map"}
    finally:
        stopped(group, worker)


def test_the_clock_master_cannot_share_a_worker():
    from coopdrive.runtime.runner import ServiceRunner
    from coopdrive.runtime.shared_worker import SharedWorker
    from coopdrive.services.sim.service import SimService

    worker = SharedWorker("world")
    runner = ServiceRunner(SimService, SimService.Config(), "world", BusConfig(), ClockMode.SIM,
                           inbox=worker.inbox())
    try:
        with pytest.raises(ValueError, match="owns the clock"):
            worker.add("world/sim", runner)
    finally:
        runner.bus.close()
