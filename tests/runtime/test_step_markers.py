"""A lockstep step's marker travels with the step's own messages, over real Zenoh sessions."""

import queue
import time

import pytest

from coopdrive.bus import Bus, BusConfig, KeyLayout
from coopdrive.runtime.runner import ClockMode, ServiceRunner
from coopdrive.runtime.service import Service
from coopdrive.v1 import control_pb2, sim_pb2

STEP_S = 0.02
DEADLINE_S = 10.0
QUIET_S = 0.5


class CommandSender(Service):
    """Stands in for control: sends `commands_per_step` commands on each 50 Hz tick."""

    name = "control"

    def start(self) -> None:
        self.commands_per_step = 0
        self.ctx.every(STEP_S, self.on_tick)

    def on_tick(self, now_s: float) -> None:
        for _ in range(self.commands_per_step):
            self.ctx.publish("control/command", control_pb2.ControlCommand(accel_request_mps2=0.5))


class CommandReceiver(Service):
    """Stands in for actuation: takes control's commands, so it waits for control's steps."""

    name = "actuation"

    def start(self) -> None:
        self.ctx.subscribe("control/command", lambda envelope: None)


def received(source: queue.Queue, deadline_s: float = DEADLINE_S):
    return source.get(timeout=deadline_s)


def nothing_arrives(source: queue.Queue) -> bool:
    try:
        source.get(timeout=QUIET_S)
    except queue.Empty:
        return True
    return False


@pytest.fixture
def sender_and_observer(endpoint):
    observer = Bus(BusConfig(listen=[endpoint]))
    runner = ServiceRunner(CommandSender, CommandSender.Config(), "ego", BusConfig(connect=[endpoint]), ClockMode.SIM)
    runner.service.start()
    layout = KeyLayout()
    commands: queue.Queue = queue.Queue()
    quiet_markers: queue.Queue = queue.Queue()
    everything: queue.Queue = queue.Queue()
    observer.subscribe("ego", "control/command", commands.put)
    observer.subscribe_key(layout.step_done("ego", "control/command"), lambda _key, marker: quiet_markers.put(marker))
    observer.subscribe_key(layout.all_topics("ego"), lambda key, _message: everything.put(key))
    end = time.monotonic() + DEADLINE_S
    while runner.bus.peer_count() == 0:
        assert time.monotonic() < end, "the two sessions never connected"
        time.sleep(0.05)
    time.sleep(0.5)  # the observer's subscriptions reach the sender
    yield runner, commands, quiet_markers, everything
    runner.bus.close()
    observer.close()


def step_marker(envelope) -> sim_pb2.StepDone:
    marker = sim_pb2.StepDone()
    marker.ParseFromString(envelope.attachment)
    return marker


def test_the_marker_rides_on_the_last_message_a_step_sent_on_a_topic(sender_and_observer):
    runner, commands, quiet_markers, _ = sender_and_observer
    runner.service.commands_per_step = 2
    runner.run_lockstep_step(4, 4 * STEP_S)
    first, second = received(commands), received(commands)
    assert first.attachment is None
    marker = step_marker(second)
    assert marker.step == 4 and marker.service == "control"
    assert marker.next_step == 5  # a 50 Hz service promises nothing beyond the next step
    assert marker.sequences["ego/control/command"] == second.message.header.sequence == 2
    assert nothing_arrives(quiet_markers), "a topic the step used needs no marker of its own"


def test_a_topic_the_step_left_quiet_gets_the_marker_on_a_key_wildcards_do_not_match(sender_and_observer):
    runner, commands, quiet_markers, everything = sender_and_observer
    runner.service.commands_per_step = 1
    runner.run_lockstep_step(0, 0.0)
    assert received(everything) == "coopdrive/ego/control/command"
    assert step_marker(received(commands)).step == 0
    runner.service.commands_per_step = 0
    runner.run_lockstep_step(1, STEP_S)
    marker = received(quiet_markers)
    assert marker.step == 1 and marker.sequences["ego/control/command"] == 1
    assert nothing_arrives(everything), "a recorder listening to every topic would have stored the marker"


def test_a_follower_takes_a_marker_riding_on_data_as_its_upstream_finishing_the_step(endpoint):
    sender = ServiceRunner(CommandSender, CommandSender.Config(), "ego", BusConfig(listen=[endpoint]), ClockMode.SIM)
    receiver = ServiceRunner(CommandReceiver, CommandReceiver.Config(), "ego", BusConfig(connect=[endpoint]),
                             ClockMode.SIM)
    try:
        sender.service.start()
        receiver.service.start()
        end = time.monotonic() + DEADLINE_S
        while receiver.bus.peer_count() == 0:
            assert time.monotonic() < end, "the two sessions never connected"
            time.sleep(0.05)
        time.sleep(0.5)
        sender.service.commands_per_step = 1
        sender.run_lockstep_step(6, 6 * STEP_S)
        events = receiver.context.events
        (data_kind, command), (done_kind, done) = events.next_event(DEADLINE_S), events.next_event(DEADLINE_S)
        assert (data_kind.name, command.topic) == ("DATA", "control/command")
        # Right behind the command, as if control had sent its own marker: step 6 done, one command counted.
        assert done_kind.name == "DONE"
        participant, step, next_step, sequences = done
        assert (participant, step, next_step, sequences) == ("ego/control", 6, 7, {"ego/control/command": 1})
        assert events.next_event(QUIET_S) is None, "no separate marker follows"
    finally:
        sender.bus.close()
        receiver.bus.close()


def test_a_quiet_topic_marker_is_sent_only_while_some_service_waits_for_it(endpoint):
    sender, waiter = Bus(BusConfig(listen=[endpoint])), Bus(BusConfig(connect=[endpoint]))
    key = KeyLayout().step_done("ego", "actuation/status")
    markers: queue.Queue = queue.Queue()
    try:
        assert not sender.put_if_subscribed(key, sim_pb2.StepDone(step=1)), "sent with nobody listening"
        waiter.subscribe_key(key, lambda _key, marker: markers.put(marker))
        end = time.monotonic() + DEADLINE_S
        while not sender.put_if_subscribed(key, sim_pb2.StepDone(step=2)):
            assert time.monotonic() < end, "the waiting subscriber never matched"
            time.sleep(0.05)
        assert received(markers).step == 2
    finally:
        waiter.close()
        sender.close()


def _until(condition, what: str) -> None:
    end = time.monotonic() + DEADLINE_S
    while not condition():
        assert time.monotonic() < end, what
        time.sleep(0.05)


def test_the_marker_stops_when_its_waiting_subscriber_leaves_and_starts_again_when_one_comes_back(endpoint):
    sender = Bus(BusConfig(listen=[endpoint]))
    key = KeyLayout().step_done("ego", "actuation/status")
    try:
        for step in range(3):  # the matching status is kept between puts: each change must reach it
            waiter = Bus(BusConfig(connect=[endpoint]))
            markers: queue.Queue = queue.Queue()
            waiter.subscribe_key(key, lambda _key, marker: markers.put(marker))
            _until(lambda: sender.put_if_subscribed(key, sim_pb2.StepDone(step=step)), "the waiter never matched")
            assert received(markers).step == step
            waiter.close()
            _until(lambda: not sender.put_if_subscribed(key, sim_pb2.StepDone(step=step)),
                   "still sent after the waiter left")
    finally:
        sender.close()
