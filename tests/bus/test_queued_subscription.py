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


def test_every_message_arrives_in_order_on_the_subscription_s_own_thread(hub, sender):
    received: list[tuple[int, str]] = []

    def note(_key, message) -> None:
        received.append((message.header.sequence, threading.current_thread().name))

    hub.subscribe_key_queued("coopdrive/**", note)
    time.sleep(0.3)  # the subscription reaches the sender
    send_numbered(sender)
    wait_until(lambda: len(received) >= MESSAGES)
    assert [sequence for sequence, _ in received] == list(range(1, MESSAGES + 1))
    assert {thread for _, thread in received} == {"queued coopdrive/**"}


def test_a_full_queue_holds_the_sender_back_instead_of_dropping(hub, sender, monkeypatch):
    monkeypatch.setattr(session, "QUEUED_SUBSCRIPTION_CAPACITY", 10)
    received: list[int] = []

    def slow(_key, message) -> None:
        time.sleep(0.001)
        received.append(message.header.sequence)

    hub.subscribe_key_queued("coopdrive/**", slow)
    time.sleep(0.3)
    send_numbered(sender, 500)
    wait_until(lambda: len(received) >= 500)
    assert received == list(range(1, 501))


def test_a_failing_callback_costs_its_message_only_and_close_ends_the_thread(hub, sender, caplog):
    received: list[int] = []

    def fails_on_the_first(_key, message) -> None:
        if message.header.sequence == 1:
            raise RuntimeError("broken handler")
        received.append(message.header.sequence)

    hub.subscribe_key_queued("coopdrive/**", fails_on_the_first)
    time.sleep(0.3)
    send_numbered(sender, 100)
    wait_until(lambda: len(received) >= 99)
    assert received == list(range(2, 101))
    assert "a queued subscriber's callback failed on coopdrive/ego/ego/state" in caplog.text
    hub.close()
    assert not any(thread.name == "queued coopdrive/**" for thread in threading.enumerate())
