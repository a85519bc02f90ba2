"""The gateway under load: the follow loop's sensor -> command latency during one realtime run with the gateway,
in alternating windows without WebSocket clients and with 50 clients on /ws (one never reads), and the
gateway's memory over the run.

Interleaving the two conditions within one run compares them under the same machine load: on a shared
machine two separate runs differ in p99 by more than the clients' effect. Latency is measured as bench_follow
measures it. The clients get COOPDRIVE_BENCH_GATEWAY_S seconds in all (default 20; the acceptance of the gateway
issue is 60), and the run lasts twice that.
"""

from __future__ import annotations

import asyncio
import multiprocessing
import os
import socket
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import websockets
from rich.console import Console
from rich.table import Table

from bench.sizes import sized
from bench.step_latency import StepLatency
from coopdrive.launch.ports import free_tcp_port
from coopdrive.launch.run import RunOptions, run_scenario

DURATION_ENV = "COOPDRIVE_BENCH_GATEWAY_S"
DEFAULT_DURATION_S = sized(20.0, 2.0)
CLIENTS = sized(50, 2)
WINDOW_S = sized(5.0, 1.0)
# Latencies this soon after a window starts are left out: the clients are still (dis)connecting.
SETTLE_S = sized(1.0, 0.2)
CONNECT_RETRY_S = 0.2
GATEWAY_START_TIMEOUT_S = 30.0


def gateway_pid() -> int | None:
    """The gateway child of this process: run_scenario does not expose its processes."""
    me = str(os.getpid())
    for proc in Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            ppid = (proc / "stat").read_text().rsplit(")", 1)[1].split()[1]
            command = (proc / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if ppid == me and b"gateway" in command:
            return int(proc.name)
    return None


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
        self._stop = context.Event()
        self._connections = context.Value("i", 0)
        self._frames = context.Value("i", 0)
        self._process = context.Process(target=_serve_clients, daemon=True, args=(
            f"ws://127.0.0.1:{port}/ws", count, self.active, self._stop, self._connections, self._frames))

    @property
    def connections(self) -> int:
        return self._connections.value

    @property
    def frames(self) -> int:
        return self._frames.value

    def start(self) -> None:
        self._process.start()

    def stop(self) -> None:
        self._stop.set()
        self._process.join(10.0)
        if self._process.is_alive():
            self._process.kill()


def _serve_clients(url: str, count: int, active, stop, connections, frames) -> None:
    os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))

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
    """perf_counter intervals with and without clients, and the gateway's RSS at the end of each window."""

    with_clients: list[tuple[float, float]] = field(default_factory=list)
    without_clients: list[tuple[float, float]] = field(default_factory=list)
    rss_kib: list[int] = field(default_factory=list)
    connections: int = 0
    frames: int = 0


def alternate_clients(port: int, clients: int, done: threading.Event, windows: Windows) -> None:
    deadline = time.monotonic() + GATEWAY_START_TIMEOUT_S
    pid = None
    while pid is None and time.monotonic() < deadline and not done.is_set():
        pid = gateway_pid()
        time.sleep(0.05)
    while pid is not None and not done.is_set() and time.monotonic() < deadline + GATEWAY_START_TIMEOUT_S:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1.0).close()
            break
        except OSError:
            time.sleep(0.1)
    if pid is None:
        return
    ws = Clients(port, clients)
    ws.start()
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
    ws.stop()
    windows.connections, windows.frames = ws.connections, ws.frames


def latencies_in(samples: np.ndarray, intervals: list[tuple[float, float]]) -> np.ndarray:
    """Latencies (column 1) of the samples whose clock arrived (column 0) in a settled part of an interval."""
    keep = np.zeros(len(samples), dtype=bool)
    for start, end in intervals:
        keep |= (samples[:, 0] >= start + SETTLE_S) & (samples[:, 0] < end)
    return samples[keep, 1]


def main() -> None:
    clients_s = float(os.environ.get(DURATION_ENV, DEFAULT_DURATION_S))
    port = free_tcp_port()
    latency = StepLatency()
    windows = Windows()
    done = threading.Event()
    watcher = threading.Thread(target=alternate_clients, args=(port, CLIENTS, done, windows), daemon=True)
    watcher.start()
    try:
        result = run_scenario(RunOptions(duration_s=2 * clients_s, realtime=True, gateway_port=port,
                                         observer=latency.observe))
    finally:
        done.set()
        watcher.join(30.0)
    samples = latency.samples()
    table = Table(title=f"follow scenario, --realtime with the gateway, {2 * clients_s:.0f} s simulated, "
                        f"{WINDOW_S:.0f} s windows without and with {CLIENTS} /ws clients (one never reads)")
    for column in ("/ws clients", "windows", "steps", "sensor -> command p50 (ms)", "p99 (ms)", "p50 ratio",
                   "p99 ratio"):
        table.add_column(column, justify="right")
    baseline = None
    for clients, intervals in ((0, windows.without_clients), (CLIENTS, windows.with_clients)):
        latencies_ms = latencies_in(samples, intervals) if samples.size else np.empty(0)
        p50, p99 = (np.percentile(latencies_ms, q) for q in (50, 99)) if latencies_ms.size else (float("nan"),) * 2
        baseline = baseline or (p50, p99)
        table.add_row(str(clients), str(len(intervals)), str(latencies_ms.size), f"{p50:.2f}", f"{p99:.2f}",
                      f"{p50 / baseline[0]:.2f}", f"{p99 / baseline[1]:.2f}")
    console = Console(width=max(Console().width, 140))
    console.print(table)
    rss = windows.rss_kib
    console.print(f"run success {result.success}; {windows.connections} client connections, "
                  f"{windows.frames} frames read; gateway RSS at the end of the first and last window with clients: "
                  + (f"{rss[0] / 1024:.1f} and {rss[-1] / 1024:.1f} MiB" if rss else "-"))


if __name__ == "__main__":
    main()
