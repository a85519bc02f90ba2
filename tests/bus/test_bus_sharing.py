"""Services composed in one process share a Zenoh session through Bus.sharing(); the bus hands a put to the
session's own subscribers itself and Zenoh carries it to other sessions'."""

import threading
import time

import pytest
import zenoh

from coopdrive.bus import Bus, BusConfig
from coopdrive.v1 import control_pb2


@pytest.fixture
def siblings(hub):
    """sibling(): another Bus on the session of `hub` (conftest: the session's first Bus); each closed at the end."""
    made = []

    def sibling() -> Bus:
        made.append(hub.sharing())
        return made[-1]

    yield sibling
    for bus in made:
        bus.close()


def test_a_message_put_on_a_shared_bus_reaches_a_subscriber_on_its_sibling(siblings):
    publisher, subscriber = siblings(), siblings()
    received, arrived = [], threading.Event()
    subscriber.subscribe("v1", "control/command", lambda envelope: (received.append(envelope), arrived.set()))
    publisher.publish("v1", "control/command", control_pb2.ControlCommand(accel_request_mps2=-1.5))
    assert arrived.wait(5.0)
    assert received[0].vehicle_id == "v1"
    assert received[0].message.accel_request_mps2 == -1.5


def test_closing_a_shared_bus_leaves_the_session_open_for_the_others(endpoint):
    owner = Bus(BusConfig(listen=[endpoint]))
    shared = owner.sharing()
    shared.close()
    assert not owner.session.is_closed()
    owner.close()
    assert owner.session.is_closed()


class Heard:
    """What one subscriber got, each message once with its attachment."""

    def __init__(self):
        self.messages: list = []
        self.changed = threading.Condition()

    def __call__(self, envelope) -> None:
        with self.changed:
            self.messages.append((envelope.vehicle_id, envelope.message.accel_request_mps2, envelope.attachment))
            self.changed.notify_all()

    def wait_for(self, count: int, timeout_s: float = 5.0) -> list:
        with self.changed:
            self.changed.wait_for(lambda: len(self.messages) >= count, timeout_s)
            return list(self.messages)


def command(accel_mps2: float) -> control_pb2.ControlCommand:
    return control_pb2.ControlCommand(accel_request_mps2=accel_mps2)


def heard_from(bus: Bus, key: str, timeout_s: float = 10.0) -> None:
    """Waits until a subscriber in another session matches what `bus` puts on `key`."""
    probe = bus.session.declare_publisher(key, allowed_destination=zenoh.Locality.REMOTE)
    end = time.monotonic() + timeout_s
    try:
        while not probe.matching_status.matching:
            assert time.monotonic() < end, f"no other session's subscriber matched {key}"
            time.sleep(0.05)
    finally:
        probe.undeclare()


def test_a_put_reaches_the_session_s_own_and_another_session_s_subscribers_each_exactly_once(endpoint, hub,
                                                                                          siblings):
    here, elsewhere = siblings(), Bus(BusConfig(connect=[endpoint], listen=[]))
    heard_here, heard_elsewhere, heard_all_vehicles = Heard(), Heard(), Heard()
    try:
        here.subscribe("v1", "control/command", heard_here)
        here.subscribe("*", "control/command", heard_all_vehicles)
        elsewhere.subscribe("v1", "control/command", heard_elsewhere)
        key = hub.layout.topic("v1", "control/command")
        heard_from(hub, key)
        heard_from(elsewhere, key)
        hub.put(key, command(-1.5), attachment=b"marker")
        elsewhere.publish("v1", "control/command", command(0.5))
        both = [("v1", -1.5, b"marker"), ("v1", 0.5, None)]
        assert sorted(heard_here.wait_for(2)) == sorted(both)
        assert sorted(heard_all_vehicles.wait_for(2)) == sorted(both)
        assert sorted(heard_elsewhere.wait_for(2)) == sorted(both)
        time.sleep(0.3)  # nothing more comes: no second delivery through Zenoh
        assert len(heard_here.messages) == len(heard_all_vehicles.messages) == len(heard_elsewhere.messages) == 2
    finally:
        elsewhere.close()


def test_a_closed_sibling_hears_nothing_more_and_a_marker_only_it_wanted_is_not_sent(hub, siblings):
    subscriber = siblings()
    heard = Heard()
    key = hub.layout.topic("v1", "control/command")
    subscriber.subscribe("v1", "control/command", heard)
    assert hub.put_if_subscribed(key, command(-1.0)), "a subscriber in the same session hears it"
    assert heard.wait_for(1) == [("v1", -1.0, None)]
    subscriber.close()
    assert not hub.put_if_subscribed(key, command(-2.0)), "sent with nobody listening"
    hub.put(key, command(-3.0))
    time.sleep(0.3)
    assert heard.messages == [("v1", -1.0, None)]


def test_a_subscriber_that_raises_is_counted_and_logged_once_and_costs_no_one_else_their_message(
        endpoint, hub, siblings, caplog):
    """Here (the bus's own delivery) and in another session (through Zenoh) alike."""
    heard = Heard()
    failing_here, elsewhere = siblings(), Bus(BusConfig(connect=[endpoint], listen=[]))

    def broken(_envelope):
        raise RuntimeError("broken subscriber")

    try:
        failing_here.subscribe("v1", "control/command", broken)
        elsewhere.subscribe("v1", "control/command", broken)
        siblings().subscribe("v1", "control/command", heard)
        key = hub.layout.topic("v1", "control/command")
        heard_from(hub, key)
        for accel_mps2 in (-1.0, -2.0):
            hub.put(key, command(accel_mps2))
        assert heard.wait_for(2) == [("v1", -1.0, None), ("v1", -2.0, None)]
        end = time.monotonic() + 5.0
        while elsewhere.callback_errors < 2 and time.monotonic() < end:
            time.sleep(0.05)
        assert (failing_here.callback_errors, elsewhere.callback_errors) == (2, 2)
        failures = [r.message for r in caplog.records if r.levelname == "ERROR"]
        assert failures == ["a subscriber to coopdrive/v1/control/command failed (later failures on this key are only "
                            "counted)"] * 2
    finally:
        elsewhere.close()


def test_a_session_that_subscribes_after_puts_nobody_else_heard_gets_the_puts_from_then_on(endpoint):
    # Puts go into Zenoh only while another session hears their key: the first puts here go nowhere, and the
    # subscriber that comes later must still be found and get what follows.
    publisher = Bus(BusConfig(listen=[endpoint]))
    try:
        for accel_mps2 in (-0.5, -1.0):
            publisher.publish("v1", "control/command", control_pb2.ControlCommand(accel_request_mps2=accel_mps2))
        listener = Bus(BusConfig(connect=[endpoint]))
        received, arrived = [], threading.Event()
        listener.subscribe("v1", "control/command", lambda envelope: (received.append(envelope), arrived.set()))
        end = time.monotonic() + 5.0
        while not arrived.is_set():
            assert time.monotonic() < end, "the later subscriber never got a put"
            publisher.publish("v1", "control/command", control_pb2.ControlCommand(accel_request_mps2=-2.0))
            arrived.wait(0.05)
        assert all(envelope.message.accel_request_mps2 == -2.0 for envelope in received)
        listener.close()
    finally:
        publisher.close()
