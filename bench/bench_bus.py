"""Bus latency: coopdrive's typed layer against raw Zenoh put/subscribe, two processes, same run; and the typed
bus over the vehicle's mutual TLS against plain TCP, through a router (bench/bus_over_mtls.py).

A pinger publishes, an echo process sends each message straight back; one-way latency is half
the round trip. The raw path sends bytes with a plain callback; the typed path goes through
Bus.publish / Bus.subscribe with protobuf encode/decode and the runtime's worker queue.
"""

from __future__ import annotations

import multiprocessing
import queue
import statistics
import time

import numpy as np
from rich.console import Console
from rich.table import Table

from bench.failure import BenchFailed
from bench.bus_over_mtls import measure_both, one_way_latencies_us
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_about import turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint

ROUND_TRIPS = sized(2000, 20)
WARMUP = sized(100, 5)
# Rounds of raw then typed, each with its own echo processes (bench/turn_about.py): the typed-to-raw ratio's interval
# comes from them (bench/turn_spread.py).
ROUNDS = sized(3, 1)
# The echo process starts as a new interpreter: on a loaded machine that takes longer than any fixed sleep.
ECHO_START_TIMEOUT_S = 60.0
# After the echo has subscribed, Zenoh's routes between the two sessions settle before the first ping.
ROUTE_SETTLE_S = 0.5


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

    def send(index: int) -> None:
        if typed:
            state.header.sequence = index + 1
            bus.publish("bench", "ego/state", state)
        else:
            raw_publisher.put(payload)

    samples = one_way_latencies_us(send, inbox, path, ROUND_TRIPS, WARMUP)
    echo.join(timeout=10)
    bus.close()
    return samples


def main() -> list[Figure]:
    raw_rounds, typed_rounds = turns([lambda: _measure(typed=False), lambda: _measure(typed=True)], ROUNDS)
    raw, typed = np.concatenate(raw_rounds), np.concatenate(typed_rounds)
    table = Table(title=f"bus one-way latency, 2 processes, {ROUNDS} rounds of {ROUND_TRIPS} round trips, "
                        f"turn about (us)")
    for column in ("path", "p50", "p99", "ratio p50 to raw"):
        table.add_column(column, justify="right")
    raw_p50 = np.percentile(raw, 50)
    figures = []
    for name, samples in (("raw zenoh bytes", raw), ("coopdrive typed", typed)):
        p50, p99 = np.percentile(samples, 50), np.percentile(samples, 99)
        table.add_row(name, f"{p50:.0f}", f"{p99:.0f}", f"{p50 / raw_p50:.2f}")
        figures += [Figure(f"{name} p50", p50, Unit.US), Figure(f"{name} p99", p99, Unit.US)]
    Console().print(table)
    spread = turn_ratio_spread([np.percentile(samples, 50) for samples in typed_rounds],
                               [np.percentile(samples, 50) for samples in raw_rounds])
    return (figures + [ratio("coopdrive typed p50 to raw", np.percentile(typed, 50) / raw_p50, "raw zenoh bytes p50",
                             spread=spread)]
            + _security_figures())


def _security_figures() -> list[Figure]:
    """The typed bus through a router, over mTLS with the access rules and over plain TCP, in one table: latency
    percentiles of every round's samples together, throughput the mean of the rounds' bursts; each ratio's interval
    from its rounds."""
    paths = measure_both()
    table = Table(title=f"typed bus through a router, 2 client processes: mTLS + access control vs plain TCP "
                        f"({len(paths['mtls'])} rounds, turn about)")
    for column in ("link", "p50 (us)", "p99 (us)", "throughput (msg/s)"):
        table.add_column(column, justify="right")
    figures, pooled, throughput = [], {}, {}
    for name, rounds in paths.items():
        pooled[name] = np.concatenate([measured.latency_us for measured in rounds])
        throughput[name] = [measured.throughput_per_s for measured in rounds]
        p50, p99 = np.percentile(pooled[name], 50), np.percentile(pooled[name], 99)
        mean_per_s = statistics.fmean(throughput[name])
        table.add_row(name, f"{p50:.0f}", f"{p99:.0f}", f"{mean_per_s:,.0f}")
        figures += [Figure(f"routed {name} p50", p50, Unit.US), Figure(f"routed {name} p99", p99, Unit.US),
                    Figure(f"routed {name} throughput", mean_per_s, Unit.PER_S)]
    Console().print(table)

    def percentile_ratio(percentile: float) -> tuple[float, float | None]:
        per_round = [[np.percentile(measured.latency_us, percentile) for measured in paths[name]]
                     for name in ("mtls", "plain tcp")]
        return (np.percentile(pooled["mtls"], percentile) / np.percentile(pooled["plain tcp"], percentile),
                turn_ratio_spread(*per_round))

    p50_ratio, p50_spread = percentile_ratio(50)
    p99_ratio, p99_spread = percentile_ratio(99)
    return figures + [
        ratio("routed mtls p50 to plain tcp", p50_ratio, "routed plain tcp p50", spread=p50_spread),
        ratio("routed mtls p99 to plain tcp", p99_ratio, "routed plain tcp p99", spread=p99_spread),
        ratio("routed mtls throughput to plain tcp",
              statistics.fmean(throughput["mtls"]) / statistics.fmean(throughput["plain tcp"]),
              "routed plain tcp throughput", Better.HIGHER,
              spread=turn_ratio_spread(throughput["mtls"], throughput["plain tcp"]))]
