"""Services composed in one process share a Zenoh session through Bus.sharing()."""

import threading

from coopdrive.bus import Bus, BusConfig
from coopdrive.v1 import control_pb2


def test_a_message_put_on_a_shared_bus_reaches_a_subscriber_on_its_sibling(endpoint):
    owner = Bus(BusConfig(listen=[endpoint]))
    publisher, subscriber = owner.sharing(), owner.sharing()
    received, arrived = [], threading.Event()
    try:
        subscriber.subscribe("v1", "control/command", lambda envelope: (received.append(envelope), arrived.set()))
        publisher.publish("v1", "control/command", control_pb2.ControlCommand(accel_request_mps2=-1.5))
        assert arrived.wait(5.0)
        assert received[0].vehicle_id == "v1"
        assert received[0].message.accel_request_mps2 == -1.5
    finally:
        publisher.close()
        subscriber.close()
        owner.close()


def test_closing_a_shared_bus_leaves_the_session_open_for_the_others(endpoint):
    owner = Bus(BusConfig(listen=[endpoint]))
    shared = owner.sharing()
    shared.close()
    assert not owner.session.is_closed()
    owner.close()
    assert owner.session.is_closed()
