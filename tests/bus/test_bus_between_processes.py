"""Typed messages crossing real processes over Zenoh, service presence, and clean shutdown."""

import os
import queue
import signal
import time
from pathlib import Path

import zenoh

from coopdrive.bus.keys import KeyLayout
from coopdrive.v1 import diagnostics_pb2

# A service ends within this long of SIGTERM (measured: 0.06-0.07 s).
SIGTERM_STOP_S = 3.0

DEADLINE_S = 30.0


def wait_for(source: queue.Queue, predicate, deadline_s=DEADLINE_S):
    end = time.monotonic() + deadline_s
    while time.monotonic() < end:
        try:
            item = source.get(timeout=0.5)
        except queue.Empty:
            continue
        if predicate(item):
            return item
    raise AssertionError("nothing matching arrived before the deadline")


def test_a_service_process_publishes_typed_messages_with_a_filled_header(hub, endpoint, spawn):
    received: queue.Queue = queue.Queue()
    hub.subscribe("ego", "planner/behaviour", received.put)
    spawn("service", "planner", "--vehicle", "ego", "--connect", endpoint)
    first = wait_for(received, lambda e: True)
    second = wait_for(received, lambda e: e.message.header.sequence > first.message.header.sequence)
    assert type(first.message).DESCRIPTOR.full_name == "coopdrive.v1.BehaviourRequest"
    assert first.vehicle_id == "ego" and first.topic == "planner/behaviour"
    assert first.message.header.sender == "planner" and first.message.header.vehicle_id == "ego"
    assert first.message.desired_speed_mps == 25.0
    assert second.message.header.sent_time_s > first.message.header.sent_time_s


def test_a_running_service_shows_a_liveliness_token_and_answers_its_info_query(hub, endpoint, spawn):
    layout = KeyLayout()
    spawn("service", "control", "--vehicle", "car7", "--connect", endpoint, "--set", "period_s=0.05")
    end = time.monotonic() + DEADLINE_S
    while layout.liveliness("car7", "control") not in hub.alive_tokens(layout.all_liveliness()):
        assert time.monotonic() < end, "no liveliness token from the control service"
        time.sleep(0.2)
    [info] = hub.query(layout.service_info("car7", "control"), diagnostics_pb2.ServiceInfo)
    assert info.service == "control" and info.vehicle_id == "car7" and info.state == "running"
    assert '"period_s":0.05' in info.config_json.replace(" ", "")


def test_a_malformed_payload_is_counted_and_the_service_keeps_running_on_its_plain_loopback_session(
        hub, endpoint, spawn):
    diagnostics: queue.Queue = queue.Queue()
    hub.subscribe("ego", "diagnostics/planner", diagnostics.put)
    spawn("service", "planner", "--vehicle", "ego", "--connect", endpoint)
    wait_for(diagnostics, lambda e: True)
    garbage = hub.session.declare_publisher("coopdrive/ego/scene", encoding=zenoh.Encoding.APPLICATION_PROTOBUF)
    for _ in range(3):
        garbage.put(b"\xff\xff\xff\x0f not a protobuf")
    report = wait_for(diagnostics, lambda e: e.message.counters["bus_decode_errors"] >= 3)
    assert report.message.header.sender == "planner"
    assert (report.message.message, report.message.counters["bus_authenticated"]) == ("bus plain-loopback", 0.0)
    # each time trigger's missed periods are in the diagnostics too
    assert "overruns__publish_diagnostics" in report.message.counters


def test_sigterm_stops_a_service_promptly_and_cleanly(hub, endpoint, spawn):
    received: queue.Queue = queue.Queue()
    hub.subscribe("ego", "planner/behaviour", received.put)
    process = spawn("service", "planner", "--vehicle", "ego", "--connect", endpoint)
    wait_for(received, lambda e: True)
    stopped_at = time.monotonic()
    process.send_signal(signal.SIGTERM)
    assert process.wait(timeout=10) == 0
    assert time.monotonic() - stopped_at < SIGTERM_STOP_S


def nice_values_of_threads(pid: int) -> list[int]:
    values = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
        values.append(int(fields[16]))  # field 19 of stat; fields[0] here is field 3
    return values


def test_a_service_configured_with_cpu_nice_runs_every_thread_at_that_lower_priority(hub, endpoint, spawn):
    layout = KeyLayout()
    process = spawn("service", "planner", "--vehicle", "ego", "--connect", endpoint, "--set", "cpu_nice=5")
    end = time.monotonic() + DEADLINE_S
    while layout.liveliness("ego", "planner") not in hub.alive_tokens(layout.all_liveliness()):
        assert time.monotonic() < end, "no liveliness token from the planner"
        time.sleep(0.2)
    threads = nice_values_of_threads(process.pid)
    assert len(threads) > 1 and set(threads) == {os.nice(0) + 5}
