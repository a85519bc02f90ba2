"""The typed bus over the vehicle's mutual TLS (with its access control) against plain TCP, like for like: in both,
two client processes reach each other through a `coopdrive router` process on loopback, as the vehicle's services
do; only the router's link (tls with the credentials `coopdrive pki bus` makes, or tcp without rules) differs.

The pinger holds geolocation's certificate (it puts ego/state), the echo actuation's (it reads ego/state and puts
can/vehicle, which geolocation reads): what the rules allow each. Latency is half a round trip; throughput is the
rate at which the echo receives a burst of ego/state (Bus.publish blocks rather than drops, so none is lost).
"""

from __future__ import annotations

import multiprocessing
import queue
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from bench.failure import BenchFailed
from bench.sizes import sized
from bench.turn_about import turns
from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port

ROUND_TRIPS = sized(2000, 20)
WARMUP = sized(100, 5)
BURST = sized(20000, 200)
# Turns of the two paths: measured once each, two quiet runs of one commit moved the p50 ratio by 21 %.
ROUNDS = sized(3, 1)
VEHICLE = "bench"
START_TIMEOUT_S = 60.0
ECHO_TIMEOUT_S = 5.0
# After the first echo, the primes still in flight come back within this.
ROUTE_SETTLE_S = 0.5


@dataclass(frozen=True)
class BusPath:
    """How each side opens its session: a config file (mTLS) or a plain TCP client of the router."""
    name: str
    router_arguments: tuple[str, ...]
    endpoint: str
    credentials: Path | None

    def config(self, holder: str) -> BusConfig:
        if self.credentials is None:
            return BusConfig(connect=[self.endpoint], listen=[], mode="client")
        return BusConfig(zenoh_config_file=str(self.credentials / holder / "zenoh.json5"))


@dataclass(frozen=True)
class PathFigures:
    latency_us: np.ndarray
    throughput_per_s: float


def measure_both(rounds: int = ROUNDS) -> dict[str, list[PathFigures]]:
    """{"plain tcp": [...], "mtls": [...]}: each through its own router (started for each measurement), turn about in
    `rounds` rounds, so that a load that comes and goes weighs on both and each ratio gets its interval from its
    rounds (bench/turn_spread.py)."""
    with tempfile.TemporaryDirectory(prefix="bench-bus-mtls-") as folder:
        plain_endpoint = f"tcp/127.0.0.1:{free_tcp_port()}"
        tls_endpoint = f"tls/127.0.0.1:{free_tcp_port()}"
        credentials = Path(folder) / "credentials"
        _run_cli("pki", "bus", str(credentials), "--vehicle", VEHICLE, "--router", tls_endpoint)
        paths = [BusPath("plain tcp", ("--listen", plain_endpoint), plain_endpoint, None),
                 BusPath("mtls", ("--config", str(credentials / "router" / "zenohd.json5"), "--listen", tls_endpoint),
                         tls_endpoint, credentials)]
        measured = turns([lambda path=path: _measure(path) for path in paths], rounds)
        return {path.name: figures for path, figures in zip(paths, measured)}


def _run_cli(*arguments: str) -> None:
    done = subprocess.run([sys.executable, "-m", "coopdrive.cli", *arguments], capture_output=True, text=True,
                          timeout=120)
    if done.returncode != 0:
        raise BenchFailed(f"coopdrive {arguments[0]}: {done.stderr.strip()}")


def _measure(path: BusPath) -> PathFigures:
    router = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "router", *path.router_arguments],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        if "listening" not in router.stdout.readline():
            raise BenchFailed(f"the {path.name} router did not start")
        return _ping_and_burst(path)
    finally:
        router.terminate()
        router.wait(timeout=30)


def _ping_and_burst(path: BusPath) -> PathFigures:
    from coopdrive.v1 import ego_pb2

    bus = Bus(path.config("geolocation"))
    pongs: queue.SimpleQueue = queue.SimpleQueue()
    bus.subscribe(VEHICLE, "can/vehicle", pongs.put)
    context = multiprocessing.get_context("spawn")
    ready, burst_rate = context.Event(), context.Queue()
    echo = context.Process(target=_echo, args=(path, ready, burst_rate), daemon=True)
    echo.start()
    try:
        if not ready.wait(START_TIMEOUT_S):
            raise BenchFailed(f"the {path.name} echo did not subscribe within {START_TIMEOUT_S:.0f} s")
        state = ego_pb2.EgoState(x_m=1.0, y_m=2.0, speed_mps=20.0, covariance=[0.1] * 36)
        _prime(bus, state, pongs, path.name)
        latency = _round_trips(bus, state, pongs, path.name)
        for index in range(BURST):
            state.header.sequence = index + 1
            bus.publish(VEHICLE, "ego/state", state)
        rate = burst_rate.get(timeout=START_TIMEOUT_S)
    finally:
        echo.join(timeout=10)
        bus.close()
    return PathFigures(latency, rate)


def _prime(bus: Bus, state, pongs: queue.SimpleQueue, name: str) -> None:
    """Pings (speed 0: not measured) until one comes back: a publisher puts only once the router has told it someone
    listens, so the first puts of each side may go nowhere. Then lets the last primes' echoes in and drops them."""
    end = time.monotonic() + START_TIMEOUT_S
    state.speed_mps = 0.0
    while True:
        bus.publish(VEHICLE, "ego/state", state)
        try:
            pongs.get(timeout=0.1)
            break
        except queue.Empty:
            if time.monotonic() > end:
                raise BenchFailed(f"the {name} echo never answered within {START_TIMEOUT_S:.0f} s") from None
    time.sleep(ROUTE_SETTLE_S)
    while not pongs.empty():
        pongs.get()
    state.speed_mps = 20.0


def _round_trips(bus: Bus, state, pongs: queue.SimpleQueue, name: str) -> np.ndarray:
    def send(index: int) -> None:
        state.header.sequence = index + 1
        bus.publish(VEHICLE, "ego/state", state)

    return one_way_latencies_us(send, pongs, name, ROUND_TRIPS, WARMUP)


def one_way_latencies_us(send: Callable[[int], None], replies: queue.SimpleQueue, name: str, round_trips: int,
                         warmup: int) -> np.ndarray:
    """Half of each round trip: send(index), then its echo from `replies`; the first `warmup` are not kept."""
    samples = []
    for index in range(round_trips + warmup):
        started = time.perf_counter()
        send(index)
        try:
            replies.get(timeout=ECHO_TIMEOUT_S)
        except queue.Empty:
            raise BenchFailed(f"no {name} echo of message {index} within {ECHO_TIMEOUT_S:.0f} s") from None
        if index >= warmup:
            samples.append((time.perf_counter() - started) / 2)
    return np.array(samples) * 1e6


def _echo(path: BusPath, ready, burst_rate) -> None:
    """Echoes the round trips as can/vehicle, then times the burst and reports its rate (messages per second)."""
    from coopdrive.v1 import vehicle_pb2

    bus = Bus(path.config("actuation"))
    inbox: queue.SimpleQueue = queue.SimpleQueue()
    bus.subscribe(VEHICLE, "ego/state",
                  lambda envelope: inbox.put((envelope.message.speed_mps > 0, time.perf_counter())))
    ready.set()
    measured = 0
    while measured < ROUND_TRIPS + WARMUP:
        measured += inbox.get()[0]  # a prime (speed 0) is answered too, not counted
        bus.publish(VEHICLE, "can/vehicle", vehicle_pb2.CanFrames())
    first = last = inbox.get()[1]
    for _ in range(BURST - 1):
        last = inbox.get()[1]
    burst_rate.put((BURST - 1) / max(last - first, 1e-9))
    bus.close()
