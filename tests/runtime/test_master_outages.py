"""ClockMaster outages: a participant killed and restarted at fixed steps, whatever the wall clock did."""

import logging
from collections import Counter
from types import SimpleNamespace

from coopdrive.bus.keys import KeyLayout
from coopdrive.runtime.barrier import StepBarrier
from coopdrive.runtime.dispatcher import StepDispatcher
from coopdrive.runtime.event_loop import EventLoop
from coopdrive.runtime.master import ClockMaster, ClockSettings, Outage
from coopdrive.runtime.events import RuntimeEvent
from coopdrive.runtime.step_wait import StepWait

PARTICIPANTS = ["v/control", "v/actuation"]
STEPS = 12


class Launcher(ClockMaster.Driven):
    """The simulator's side as the master sees it; its outages come true as the launcher would make them."""

    def __init__(self, runner, outages):
        self.runner = runner
        self.outages = outages
        self.counters = Counter()
        self.announced = []

    def clock_settings(self):
        return ClockSettings(step_s=0.1, participants=list(PARTICIPANTS), outages=self.outages)

    def on_outage(self, participant, restart):
        self.announced.append((self.runner.steps_run, participant, restart))
        self.runner.events.put(RuntimeEvent.ALIVE, (participant, restart))  # token gone, or back

    def count(self, counter):
        self.counters[counter] += 1


class SteppedRunner:
    """What ClockMaster needs of a service's context and Stepper, with the events a run would bring."""

    def __init__(self):
        self.events = EventLoop(None, call=lambda function: function())
        for participant in PARTICIPANTS:
            self.events.put(RuntimeEvent.ALIVE, (participant, True))
        self.clocks = []
        self.steps_run = 0
        self.barrier = StepBarrier("sim")
        self.dispatcher = StepDispatcher("sim", "world")
        self.bus = SimpleNamespace(layout=KeyLayout())
        self.log = logging.getLogger("test")
        self.published_sequences = {}
        self.time_s = 0.0

    @property
    def stopping(self):
        return self.steps_run >= STEPS

    def run_step(self, step, time_s):
        self.steps_run, self.time_s = step + 1, time_s

    def now_s(self):
        return self.time_s

    def publish_clock(self, clock, key):
        self.clocks.append((clock.step, sorted(clock.participants), key.endswith("/all")))


def run_master(outages):
    runner = SteppedRunner()
    runner.service = Launcher(runner, outages)
    master_of(runner).run()
    return runner


def master_of(runner):
    return ClockMaster(runner.service, runner, runner, StepWait(runner.barrier, runner.log, runner.service.count))


def test_a_crash_drops_the_participant_at_its_step_and_a_restart_brings_it_back_at_its_step():
    runner = run_master([Outage("v/control", crash_step=4, restart_step=8)])
    assert runner.service.announced == [(4, "v/control", False), (8, "v/control", True)]
    listed = {step: participants for step, participants, to_all in runner.clocks if not to_all}
    assert all("v/control" in listed[step] for step in (0, 3, 8, 11))
    assert all(listed[step] == ["v/actuation"] for step in (4, 5, 6, 7))
    # Each change is re-sent to every follower with the clock of the step before it.
    assert [(step, p) for step, p, to_all in runner.clocks if to_all] == [(3, ["v/actuation"]), (7, sorted(PARTICIPANTS))]
    assert runner.service.counters == {"participants_lost": 1, "participants_restarted": 1}


def test_a_restart_that_never_comes_back_leaves_the_run_going_without_it(monkeypatch):
    runner = SteppedRunner()
    runner.service = Launcher(runner, [Outage("v/control", crash_step=2, restart_step=5)])
    runner.service.on_outage = lambda participant, restart: None  # the launcher does nothing
    settings = runner.service.clock_settings()
    settings.restart_timeout_s = 0.2
    runner.service.clock_settings = lambda: settings
    monkeypatch.setattr("coopdrive.runtime.master.CRASH_TIMEOUT_S", 0.2)
    master_of(runner).run()
    assert runner.clocks[-1][1] == ["v/actuation"] and runner.steps_run == STEPS
