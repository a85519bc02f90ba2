"""The services of one process take turns in simulated time and run side by side on the wall clock."""

import threading
import time

from coopdrive.bus import Bus, BusConfig
from coopdrive.runtime.group import GroupMember, ServiceGroup
from coopdrive.runtime.runner import ClockMode, ServiceRunner
from coopdrive.runtime.service import Service

PERIOD_S = 0.02
# Longer than the period, so that two services whose handlers may overlap do overlap.
HANDLER_S = 0.03
RUN_S = 0.6


class SlowPlanner(Service):
    """A handler that keeps its service busy for HANDLER_S without holding the interpreter lock (it sleeps)."""

    name = "planner"

    def start(self) -> None:
        self.busy: list[tuple[float, float]] = []
        self.ctx.every(PERIOD_S, self.on_tick)

    def on_tick(self, _now_s: float) -> None:
        started = time.monotonic()
        time.sleep(HANDLER_S)
        self.busy.append((started, time.monotonic()))


class SlowControl(SlowPlanner):
    name = "control"


def overlaps(runners) -> int:
    """How many pairs of busy intervals of different services overlap."""
    first, second = (runner.service.busy for runner in runners)
    return sum(1 for a0, a1 in first for b0, b1 in second if a0 < b1 and b0 < a1)


def run_for(runners, seconds: float) -> None:
    threads = [threading.Thread(target=runner.run) for runner in runners]
    for thread in threads:
        thread.start()
    time.sleep(seconds)
    for runner in runners:
        runner.request_stop("test over")
    for thread in threads:
        thread.join(5.0)


def test_services_sharing_a_turn_never_handle_events_at_the_same_time():
    bus = Bus(BusConfig())
    turn = threading.Lock()
    runners = [ServiceRunner(cls, cls.Config(), "ego", None, ClockMode.WALL, bus=bus.sharing(), turn=turn)
               for cls in (SlowPlanner, SlowControl)]
    try:
        run_for(runners, RUN_S)
    finally:
        bus.close()
    assert all(len(runner.service.busy) >= 5 for runner in runners)
    assert overlaps(runners) == 0


def run_group(group: ServiceGroup, seconds: float) -> None:
    worker = threading.Thread(target=group.run)
    worker.start()
    time.sleep(seconds)
    group.request_stop("test over")
    worker.join(5.0)


def members():
    return [GroupMember(cls, cls.Config(), "ego") for cls in (SlowPlanner, SlowControl)]


def test_on_the_wall_clock_the_services_of_a_group_run_side_by_side():
    group = ServiceGroup(members(), BusConfig(), ClockMode.WALL)
    run_group(group, RUN_S)
    assert group.turn is None
    assert overlaps(group.runners) > 0


def test_in_simulated_time_every_service_of_a_group_holds_the_group_s_one_turn():
    group = ServiceGroup(members(), BusConfig(), ClockMode.SIM)
    run_group(group, 0.1)
    assert group.turn is not None
    assert all(runner.turn is group.turn for runner in group.runners)
