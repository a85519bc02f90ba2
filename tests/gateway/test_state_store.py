"""StateStore: latest messages, liveliness and wall-time rates, without any network."""

import threading

from coopdrive.services.gateway.state_store import StateStore
from coopdrive.v1 import ego_pb2, scene_pb2


def ego_state(speed_mps: float, sent_time_s: float) -> ego_pb2.EgoState:
    message = ego_pb2.EgoState(speed_mps=speed_mps)
    message.header.sent_time_s = sent_time_s
    return message


def test_the_latest_message_of_a_topic_replaces_the_previous_one():
    store = StateStore(["geolocation"], rate_window_s=5.0)
    store.record("geolocation", "ego/state", ego_state(10.0, 1.0), 1.0, wall_s=100.0)
    store.record("geolocation", "ego/state", ego_state(11.0, 1.1), 1.1, wall_s=100.1)
    latest = store.latest("ego/state")
    assert latest.message.speed_mps == 11.0
    assert latest.sent_time_s == 1.1


def test_a_topic_never_received_has_no_latest_message():
    store = StateStore(["scene"], rate_window_s=5.0)
    assert store.latest("scene") is None


def test_messages_from_a_service_not_watched_are_ignored():
    store = StateStore(["scene"], rate_window_s=5.0)
    store.record("stranger", "scene", scene_pb2.Scene(), 1.0, wall_s=1.0)
    snapshot = store.snapshot(wall_s=1.0)
    assert "stranger" not in snapshot.services
    assert store.latest("scene") is None


def test_a_service_is_not_alive_until_its_token_appears_and_again_once_it_goes():
    store = StateStore(["planner"], rate_window_s=5.0)
    assert not store.snapshot(0.0).services["planner"].alive
    store.set_alive("planner", True)
    assert store.snapshot(0.0).services["planner"].alive
    store.set_alive("planner", False)
    assert not store.snapshot(0.0).services["planner"].alive


def test_the_last_send_time_is_the_newest_even_when_messages_arrive_out_of_order():
    store = StateStore(["geolocation"], rate_window_s=5.0)
    store.record("geolocation", "ego/state", ego_state(1.0, 2.0), 2.0, wall_s=10.0)
    store.record("geolocation", "ego/gnss", ego_pb2.EgoState(), 1.5, wall_s=10.01)
    assert store.snapshot(10.02).services["geolocation"].last_sent_time_s == 2.0


def test_a_steady_service_reports_its_rate_over_the_wall_time_window():
    store = StateStore(["control"], rate_window_s=2.0)
    for i in range(100):  # 20 Hz for 5 s of wall time
        store.record("control", "control/command", ego_pb2.EgoState(), i * 0.05, wall_s=i * 0.05)
    assert abs(store.snapshot(wall_s=4.96).services["control"].message_rate_hz - 20.0) < 1.0


def test_a_young_service_reports_the_spacing_of_its_first_messages():
    store = StateStore(["control"], rate_window_s=5.0)
    for i in range(3):
        store.record("control", "control/command", ego_pb2.EgoState(), i * 0.1, wall_s=i * 0.1)
    assert abs(store.snapshot(wall_s=0.25).services["control"].message_rate_hz - 10.0) < 1e-9


def test_the_rate_falls_to_zero_a_window_after_a_service_goes_quiet():
    store = StateStore(["control"], rate_window_s=1.0)
    for i in range(20):
        store.record("control", "control/command", ego_pb2.EgoState(), i * 0.1, wall_s=i * 0.1)
    assert store.snapshot(wall_s=2.0).services["control"].message_rate_hz > 0
    assert store.snapshot(wall_s=3.5).services["control"].message_rate_hz == 0.0


def test_the_clock_is_unknown_until_noted():
    store = StateStore([], rate_window_s=1.0)
    assert store.snapshot(0.0).clock_s is None
    store.note_clock(12.5)
    assert store.snapshot(0.0).clock_s == 12.5


def test_readers_and_a_writer_on_other_threads_never_see_a_broken_store():
    store = StateStore(["geolocation"], rate_window_s=1.0)
    errors: list[BaseException] = []
    done = threading.Event()

    def write() -> None:
        for i in range(5_000):
            store.record("geolocation", "ego/state", ego_state(i, i * 0.01), i * 0.01, wall_s=i * 0.01)
            store.note_clock(i * 0.01)
        done.set()

    def read() -> None:
        try:
            while not done.is_set():
                snapshot = store.snapshot(wall_s=200.0)
                latest = snapshot.latest.get("ego/state")
                assert latest is None or latest.message.header.sent_time_s == latest.sent_time_s
        except BaseException as error:  # noqa: BLE001 - reported by the main thread
            errors.append(error)

    readers = [threading.Thread(target=read) for _ in range(3)]
    for reader in readers:
        reader.start()
    write()
    for reader in readers:
        reader.join()
    assert errors == []
    assert store.latest("ego/state").message.speed_mps == 4_999
