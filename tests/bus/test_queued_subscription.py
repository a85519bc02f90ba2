"""Bus.subscribe_key_queued: a subscriber of many messages (the run's recorder) takes them from a queue on a thread
of its own, every one and in order, between two real Zenoh sessions."""

import threading
import time

import pytest

from coopdrive.bus import Bus, BusConfig, session
from coopdrive.v1 import ego_pb2

MESSAGES = 2000
DEADLINE_S = 30.0
KEY = "coopdrive/ego/ego/state"


@pytest.fixture
def sender(endpoint, hub):
    bus = Bus(BusConfig(connect=[endpoint]))
    end = time.monotonic() + DEADLINE_S
    while hub.peer_count() == 0:
        assert time.monotonic() < end, "the sender never joined the hub"
        time.sleep(0.05)
    yield bus
    bus.close()


def send_numbered(bus: Bus, count: int = MESSAGES) -> None:
    for sequence in range(1, count + 1):
        state = ego_pb2.EgoState(speed_mps=20.0)
        state.header.sequence = sequence
        bus.put(KEY, state)


def wait_until(condition) -> None:
    end = time.monotonic() + DEADLINE_S
    while not condition():
        assert time.monotonic() < end, "not everything arrived before the deadline"
        time.sleep(0.05)


def sequences_through_the_queue(hub: Bus, sender: Bus, count: int, expected: int, on_message) -> list[int]:
    """Subscribes queued to every key, sends `count` numbered messages and returns, once `expected` have come
    through, the sequences the callback took: on_message(message) runs first, and one that raises takes none."""
    received: list[int] = []

    def take(_key, message) -> None:
        on_message(message)
        received.append(message.header.sequence)

    hub.subscribe_key_queued("coopdrive/**", take)
    time.sleep(0.3)  # the subscription reaches the sender
    send_numbered(sender, count)
    wait_until(lambda: len(received) >= expected)
    return received


def test_every_message_arrives_in_order_on_the_subscription_s_own_thread(hub, sender):
    threads: set[str] = set()
    received = sequences_through_the_queue(hub, sender, MESSAGES, MESSAGES,
                                           lambda _message: threads.add(threading.current_thread().name))
    assert received == list(range(1, MESSAGES + 1))
    assert threads == {"queued coopdrive/**"}


def test_a_full_queue_holds_the_sender_back_instead_of_dropping(hub, sender, monkeypatch):
    monkeypatch.setattr(session, "QUEUED_SUBSCRIPTION_CAPACITY", 10)
    received = sequences_through_the_queue(hub, sender, 500, 500, lambda _message: time.sleep(0.001))
    assert received == list(range(1, 501))


def test_a_failing_callback_costs_its_message_only_and_close_ends_the_thread(hub, sender, caplog):
    def fails_on_the_first(message) -> None:
        if message.header.sequence == 1:
            raise RuntimeError("broken handler")

    received = sequences_through_the_queue(hub, sender, 100, 99, fails_on_the_first)
    assert received == list(range(2, 101))
    assert "a queued subscriber's callback failed on coopdrive/ego/ego/state" in caplog.text
    hub.close()
    assert not any(thread.name == "queued coopdrive/**" for thread in threading.enumerate())
