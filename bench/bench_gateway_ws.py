"""The gateway under load: the follow loop's sensor -> command latency during one realtime run with the gateway,
in alternating windows without WebSocket clients and with 50 clients on /ws (one never reads), and the
gateway's memory over the run.

Interleaving the two conditions within one run compares them under the same machine load: on a shared
machine two separate runs differ in p99 by more than the clients' effect. Latency is measured as bench_follow
measures it. Each ratio carries the half-width of its 95 % bootstrap interval (bench/percentile_interval.py): a p99
of a few hundred steps moves by a fifth between two runs of the same code. The clients get COOPDRIVE_BENCH_GATEWAY_S seconds in all (default 20; the acceptance of the gateway
issue is 60), and the run lasts twice that. The gateway's process is the one the launcher says it started as
"<vehicle>/gateway" (RunOptions.on_process_started); a gateway that never starts or never answers, or clients that
never connect, fail the benchmark with the reason.
"""

from __future__ import annotations

import asyncio
import multiprocessing
import os
import queue
import socket
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import websockets
from rich.console import Console
from rich.table import Table

from bench.failure import BenchFailed, require_success
from bench.figure import Better, Figure, Unit, ratio
from bench.percentile_interval import percentile_ratio_spread
from bench.sizes import sized
from bench.step_latency import StepLatency
from coopdrive.launch.ports import free_tcp_port
from coopdrive.launch.run import RunOptions, run_scenario

DURATION_ENV = "COOPDRIVE_BENCH_GATEWAY_S"
# Quick: long enough for one window with clients after a gateway that starts slowly on a loaded host (at 3 s the
# smoke once ended before its first window with clients).
DEFAULT_DURATION_S = sized(20.0, 6.0)
CLIENTS = sized(50, 2)
WINDOW_S = sized(5.0, 1.0)
# Latencies this soon after a window starts are left out: the clients are still (dis)connecting.
SETTLE_S = sized(1.0, 0.2)
CONNECT_RETRY_S = 0.2
GATEWAY_START_TIMEOUT_S = 30.0
CLIENTS_START_TIMEOUT_S = 60.0
# How the launcher names the gateway's process: "<watched vehicle>/gateway".
GATEWAY_PROCESS_SUFFIX = "/gateway"
KIB_PER_MIB = 1024


def rss_kib(pid: int) -> int | None:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except OSError:
        return None
    return None


class Clients:
    """WebSocket clients on /ws in a process of their own, connected while `active` is set; client 0 never reads.

    They stand for tablets and laptops elsewhere: in this process they would share the interpreter lock with the
    observer that timestamps the loop's messages, and they run as SCHED_IDLE so as not to take CPU the stack
    would get on a vehicle."""

    def __init__(self, port: int, count: int):
        context = multiprocessing.get_context("spawn")
        self.active = context.Event()
        self.ready = context.Event()
        self._stop = context.Event()
        self._connections = context.Value("i", 0)
        self._frames = context.Value("i", 0)
        self._process = context.Process(target=_serve_clients, daemon=True, args=(
            f"ws://127.0.0.1:{port}/ws", count, self.active, self.ready, self._stop, self._connections, self._frames))

    @property
    def connections(self) -> int:
        return self._connections.value

    @property
    def frames(self) -> int:
        return self._frames.value

    def start(self) -> None:
        """Starts the clients' process and waits until it is ready, so its start-up is not the run's."""
        self._process.start()
        if not self.ready.wait(CLIENTS_START_TIMEOUT_S):
            self.stop()
            raise BenchFailed(f"the /ws clients' process was not ready within {CLIENTS_START_TIMEOUT_S:.0f} s")

    def stop(self) -> None:
        self._stop.set()
        self._process.join(10.0)
        if self._process.is_alive():
            self._process.kill()


def _serve_clients(url: str, count: int, active, ready, stop, connections, frames) -> None:
    os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    ready.set()

    async def client(index: int) -> None:
        while not stop.is_set():
            if not active.is_set():
                await asyncio.sleep(CONNECT_RETRY_S)
                continue
            try:
                async with websockets.connect(url, max_queue=None if index else 1) as ws:
                    with connections.get_lock():
                        connections.value += 1
                    while active.is_set() and not stop.is_set():
                        if index == 0:
                            await asyncio.sleep(CONNECT_RETRY_S)  # never reads: the server's sends back up
                            continue
                        try:
                            await asyncio.wait_for(ws.recv(), CONNECT_RETRY_S)
                            with frames.get_lock():
                                frames.value += 1
                        except asyncio.TimeoutError:
                            pass
            except (OSError, websockets.WebSocketException):
                await asyncio.sleep(CONNECT_RETRY_S)

    async def main() -> None:
        await asyncio.gather(*(client(i) for i in range(count)), return_exceptions=True)

    asyncio.run(main())


@dataclass
class Windows:
    """perf_counter intervals with and without clients, the gateway's RSS at the end of each window with them, and
    why nothing could be measured, if so."""

    with_clients: list[tuple[float, float]] = field(default_factory=list)
    without_clients: list[tuple[float, float]] = field(default_factory=list)
    rss_kib: list[int] = field(default_factory=list)
    connections: int = 0
    frames: int = 0
    failure: str | None = None


def told_gateway_pid(gateway_pids: queue.SimpleQueue, done: threading.Event) -> int | None:
    """The gateway's pid as the launcher tells it (RunOptions.on_process_started), or None if the run ends or
    GATEWAY_START_TIMEOUT_S pass first."""
    deadline = time.monotonic() + GATEWAY_START_TIMEOUT_S
    while time.monotonic() < deadline and not done.is_set():
        try:
            return gateway_pids.get(timeout=CONNECT_RETRY_S)
        except queue.Empty:
            continue
    return None


def answers(port: int, pid: int, done: threading.Event) -> bool:
    """Whether the gateway accepts connections on `port` while it runs, within GATEWAY_START_TIMEOUT_S."""
    deadline = time.monotonic() + GATEWAY_START_TIMEOUT_S
    while rss_kib(pid) is not None and not done.is_set() and time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1.0).close()
            return True
        except OSError:
            time.sleep(CONNECT_RETRY_S)
    return False


def alternate_clients(port: int, ws: Clients, done: threading.Event, windows: Windows,
                      gateway_pids: queue.SimpleQueue) -> None:
    pid = told_gateway_pid(gateway_pids, done)
    if pid is None:
        windows.failure = "the run started no gateway process (the launcher told of none)"
        return
    if not answers(port, pid, done):
        windows.failure = f"the gateway (pid {pid}) never answered on port {port}"
        return
    with_clients = False
    while not done.is_set():
        if with_clients:
            ws.active.set()
        else:
            ws.active.clear()
        start = time.perf_counter()
        done.wait(WINDOW_S)
        (windows.with_clients if with_clients else windows.without_clients).append((start, time.perf_counter()))
        sample = rss_kib(pid)
        if sample is not None and with_clients:
            windows.rss_kib.append(sample)
        with_clients = not with_clients
    ws.active.clear()
    windows.connections, windows.frames = ws.connections, ws.frames
    if not windows.connections or not windows.frames:
        windows.failure = (f"{windows.connections} /ws client connections, {windows.frames} frames read: the "
                           "clients did not load the gateway")


def latencies_in(samples: np.ndarray, intervals: list[tuple[float, float]]) -> np.ndarray:
    """Latencies (column 1) of the samples whose clock arrived (column 0) in a settled part of an interval."""
    keep = np.zeros(len(samples), dtype=bool)
    for start, end in intervals:
        keep |= (samples[:, 0] >= start + SETTLE_S) & (samples[:, 0] < end)
    return samples[keep, 1]


def main() -> list[Figure]:
    clients_s = float(os.environ.get(DURATION_ENV, DEFAULT_DURATION_S))
    port = free_tcp_port()
    latency = StepLatency()
    windows = Windows()
    done = threading.Event()
    gateway_pids: queue.SimpleQueue = queue.SimpleQueue()

    def told(name: str, pid: int) -> None:
        if name.endswith(GATEWAY_PROCESS_SUFFIX):
            gateway_pids.put(pid)

    ws = Clients(port, CLIENTS)
    ws.start()
    watcher = threading.Thread(target=alternate_clients, args=(port, ws, done, windows, gateway_pids), daemon=True)
    watcher.start()
    try:
        result = run_scenario(RunOptions(duration_s=2 * clients_s, realtime=True, gateway_port=port,
                                         observer=latency.observe, on_process_started=told))
    finally:
        done.set()
        watcher.join(30.0)
        ws.stop()
    require_success(result, "the realtime run with the gateway")
    if windows.failure is not None:
        raise BenchFailed(windows.failure)
    return latency_table(latency.samples(), windows, clients_s) + [
        Figure(f"gateway RSS, first window with {CLIENTS} clients", _mib(windows.rss_kib, 0), Unit.MIB),
        Figure(f"gateway RSS, last window with {CLIENTS} clients", _mib(windows.rss_kib, -1), Unit.MIB)]


def latency_table(samples: np.ndarray, windows: Windows, clients_s: float) -> list[Figure]:
    """Prints the latencies without and with the clients; their figures, NaN for a condition with no step."""
    table = Table(title=f"follow scenario, --realtime with the gateway, {2 * clients_s:.0f} s simulated, "
                        f"{WINDOW_S:.0f} s windows without and with {CLIENTS} /ws clients (one never reads)")
    for column in ("/ws clients", "windows", "steps", "sensor -> command p50 (ms)", "p99 (ms)", "p50 ratio",
                   "p99 ratio"):
        table.add_column(column, justify="right")
    figures, baseline, conditions = [], None, []
    for clients, intervals in ((0, windows.without_clients), (CLIENTS, windows.with_clients)):
        latencies_ms = latencies_in(samples, intervals) if samples.size else np.empty(0)
        conditions.append(latencies_ms)
        p50, p99 = (np.percentile(latencies_ms, q) for q in (50, 99)) if latencies_ms.size else (float("nan"),) * 2
        baseline = baseline or (p50, p99)
        table.add_row(str(clients), str(len(intervals)), str(latencies_ms.size), f"{p50:.2f}", f"{p99:.2f}",
                      f"{p50 / baseline[0]:.2f}", f"{p99 / baseline[1]:.2f}")
        figures += [Figure(f"{clients} clients: sensor -> command p50", p50, Unit.MS),
                    Figure(f"{clients} clients: sensor -> command p99", p99, Unit.MS)]
    Console(width=max(Console().width, 140)).print(table)
    rss = windows.rss_kib
    print(f"{windows.connections} client connections, {windows.frames} frames read; gateway RSS at the end of the "
          f"first and last window with clients: " + (f"{_mib(rss, 0):.1f} and {_mib(rss, -1):.1f} MiB" if rss else "-"))
    spreads = ([percentile_ratio_spread(*conditions, q) for q in (50, 99)] if all(c.size for c in conditions)
               else [None, None])
    print("95 % bootstrap interval of the ratios: " + ", ".join(
        f"p{q} +-{100 * spread:.0f} %" for q, spread in zip((50, 99), spreads) if spread is not None))
    return figures + [ratio(f"{CLIENTS} clients: p{q} to 0 clients'", figures[index + 2].value / figures[index].value,
                            f"0 clients: sensor -> command p{q}", Better.LOWER, spreads[index])
                      for index, q in enumerate((50, 99))]


def _mib(rss_kib: list[int], index: int) -> float:
    return rss_kib[index] / KIB_PER_MIB if rss_kib else float("nan")


if __name__ == "__main__":
    main()
