"""A lockstep follower takes only the simulator clocks of the steps its triggers run in (real Zenoh sessions)."""

import queue
import time

import pytest

from coopdrive.bus import Bus, BusConfig
from coopdrive.runtime.clock_subscription import ClockSubscription
from coopdrive.v1 import sim_pb2

STEP_S = 0.02
STEPS = 20
DEADLINE_S = 10.0
QUIET_S = 0.5


@pytest.fixture
def simulator_and_follower(endpoint):
    simulator, follower = Bus(BusConfig(listen=[endpoint])), Bus(BusConfig(connect=[endpoint]))
    end = time.monotonic() + DEADLINE_S
    while follower.peer_count() == 0:
        assert time.monotonic() < end, "the two sessions never connected"
        time.sleep(0.05)
    yield simulator, follower
    follower.close()
    simulator.close()


def clocks_taken(simulator: Bus, follower: Bus, trigger_periods_s: list[float], step_hint_s: float | None,
                 announced_step_s: float = STEP_S) -> list[int]:
    """The steps whose clocks reach a follower with these triggers when the simulator steps STEPS times."""
    taken: queue.Queue = queue.Queue()
    subscription = ClockSubscription(follower, lambda clock: taken.put(clock.step), step_hint_s)
    subscription.declare(trigger_periods_s)
    subscription.check_step(announced_step_s)
    time.sleep(QUIET_S)  # the subscriptions reach the simulator's session
    for step in range(STEPS):
        simulator.put(simulator.layout.clock_step(step), sim_pb2.SimClock(step=step, step_s=announced_step_s))
    steps = []
    try:
        while True:
            steps.append(taken.get(timeout=QUIET_S))
    except queue.Empty:
        return steps


def test_a_10_hz_service_takes_every_fifth_clock_of_a_50_hz_simulator(simulator_and_follower):
    assert clocks_taken(*simulator_and_follower, [0.1, 1.0], STEP_S) == [0, 5, 10, 15]


def test_a_25_hz_service_with_a_10_hz_trigger_takes_each_step_either_one_runs_in(simulator_and_follower):
    steps = clocks_taken(*simulator_and_follower, [0.04, 0.1], STEP_S)
    assert sorted(set(steps)) == [0, 2, 4, 5, 6, 8, 10, 12, 14, 15, 16, 18]


def test_without_the_step_every_clock_is_taken(simulator_and_follower):
    assert sorted(set(clocks_taken(*simulator_and_follower, [0.1], None))) == list(range(STEPS))


def test_a_period_that_is_no_whole_number_of_steps_takes_every_clock(simulator_and_follower):
    assert sorted(set(clocks_taken(*simulator_and_follower, [0.1, 1 / 15], STEP_S))) == list(range(STEPS))


def test_a_simulator_stepping_otherwise_than_announced_gets_every_clock_taken(simulator_and_follower):
    steps = clocks_taken(*simulator_and_follower, [0.1], STEP_S, announced_step_s=0.03)
    assert sorted(set(steps)) == list(range(STEPS))


def test_a_clock_sent_to_all_reaches_a_follower_whatever_its_triggers(simulator_and_follower):
    simulator, follower = simulator_and_follower
    taken: queue.Queue = queue.Queue()
    ClockSubscription(follower, lambda clock: taken.put(clock.step), STEP_S).declare([0.1])
    time.sleep(QUIET_S)
    simulator.put(simulator.layout.clock_to_all(), sim_pb2.SimClock(step=7))
    assert taken.get(timeout=DEADLINE_S) == 7


def test_recorders_of_every_topic_never_see_the_followers_clocks(simulator_and_follower):
    simulator, follower = simulator_and_follower
    seen: queue.Queue = queue.Queue()
    follower.subscribe_key(follower.layout.all_topics(), lambda key, _message: seen.put(key))
    time.sleep(QUIET_S)
    simulator.put(simulator.layout.clock_step(3), sim_pb2.SimClock(step=3))
    simulator.put(simulator.layout.clock_to_all(), sim_pb2.SimClock(step=4))
    with pytest.raises(queue.Empty):
        seen.get(timeout=QUIET_S)
