"""Bus latency: coopdrive's typed layer against raw Zenoh put/subscribe, two processes, same run.

A pinger publishes, an echo process sends each message straight back; one-way latency is half
the round trip. The raw path sends bytes with a plain callback; the typed path goes through
Bus.publish / Bus.subscribe with protobuf encode/decode and the runtime's worker queue.
"""

from __future__ import annotations

import multiprocessing
import queue
import time

import numpy as np
from rich.console import Console
from rich.table import Table

from bench.failure import BenchFailed
from bench.figure import Figure, Unit, ratio
from bench.sizes import sized
from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint

ROUND_TRIPS = sized(2000, 20)
WARMUP = sized(100, 5)
# The echo process starts as a new interpreter: on a loaded machine that takes longer than any fixed sleep.
ECHO_START_TIMEOUT_S = 60.0
# After the echo has subscribed, Zenoh's routes between the two sessions settle before the first ping.
ROUTE_SETTLE_S = 0.5
ECHO_TIMEOUT_S = 5.0


def _config(listen, connect) -> BusConfig:
    return BusConfig(listen=listen, connect=connect)


def _echo(endpoint: str, typed: bool, ready) -> None:
    bus = Bus(_config(["tcp/127.0.0.1:0"], [endpoint]))
    if typed:
        inbox: queue.SimpleQueue = queue.SimpleQueue()
        bus.subscribe("bench", "ego/state", inbox.put)
        ready.set()
        for _ in range(ROUND_TRIPS + WARMUP):
            envelope = inbox.get()
            bus.publish("bench", "ego/gnss", _fix_from(envelope.message))
    else:
        inbox = queue.SimpleQueue()
        bus.session.declare_subscriber("bench/raw/ping", lambda s: inbox.put(s.payload.to_bytes()))
        publisher = bus.session.declare_publisher("bench/raw/pong")
        ready.set()
        for _ in range(ROUND_TRIPS + WARMUP):
            publisher.put(inbox.get())
    time.sleep(0.5)
    bus.close()


def _fix_from(state):
    from coopdrive.v1 import gnss_pb2

    fix = gnss_pb2.GnssFix(latitude_deg=state.x_m)
    fix.header.CopyFrom(state.header)
    return fix


def _measure(typed: bool) -> np.ndarray:
    from coopdrive.v1 import ego_pb2

    endpoint = loopback_endpoint(free_tcp_port())
    bus = Bus(_config([endpoint], []))
    inbox: queue.SimpleQueue = queue.SimpleQueue()
    if typed:
        bus.subscribe("bench", "ego/gnss", inbox.put)
    else:
        bus.session.declare_subscriber("bench/raw/pong", lambda s: inbox.put(s.payload.to_bytes()))
        raw_publisher = bus.session.declare_publisher("bench/raw/ping")
    context = multiprocessing.get_context("spawn")
    ready = context.Event()
    echo = context.Process(target=_echo, args=(endpoint, typed, ready), daemon=True)
    echo.start()
    path = "typed" if typed else "raw"
    if not ready.wait(ECHO_START_TIMEOUT_S):
        raise BenchFailed(f"the {path} echo process did not subscribe within {ECHO_START_TIMEOUT_S:.0f} s")
    time.sleep(ROUTE_SETTLE_S)
    state = ego_pb2.EgoState(x_m=1.0, y_m=2.0, speed_mps=20.0, covariance=[0.1] * 36)
    payload = state.SerializeToString()
    samples = []
    for index in range(ROUND_TRIPS + WARMUP):
        started = time.perf_counter()
        if typed:
            state.header.sequence = index + 1
            bus.publish("bench", "ego/state", state)
        else:
            raw_publisher.put(payload)
        try:
            inbox.get(timeout=ECHO_TIMEOUT_S)
        except queue.Empty:
            raise BenchFailed(f"no {path} echo of message {index} within {ECHO_TIMEOUT_S:.0f} s") from None
        if index >= WARMUP:
            samples.append((time.perf_counter() - started) / 2)
    echo.join(timeout=10)
    bus.close()
    return np.array(samples) * 1e6


def main() -> list[Figure]:
    raw = _measure(typed=False)
    typed = _measure(typed=True)
    table = Table(title=f"bus one-way latency, 2 processes, {ROUND_TRIPS} round trips (us)")
    for column in ("path", "p50", "p99", "ratio p50 to raw"):
        table.add_column(column, justify="right")
    raw_p50 = np.percentile(raw, 50)
    figures = []
    for name, samples in (("raw zenoh bytes", raw), ("coopdrive typed", typed)):
        p50, p99 = np.percentile(samples, 50), np.percentile(samples, 99)
        table.add_row(name, f"{p50:.0f}", f"{p99:.0f}", f"{p50 / raw_p50:.2f}")
        figures += [Figure(f"{name} p50", p50, Unit.US), Figure(f"{name} p99", p99, Unit.US)]
    Console().print(table)
    return figures + [ratio("coopdrive typed p50 to raw", np.percentile(typed, 50) / raw_p50, "raw zenoh bytes p50")]


if __name__ == "__main__":
    main()
