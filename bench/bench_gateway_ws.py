"""The gateway under load: the follow loop's sensor -> command latency during a realtime run with the gateway,
without WebSocket clients (baseline) and with 50 clients on /ws (one never reads), and the gateway's RSS.

Latency is measured as bench_follow measures it. Each run lasts COOPDRIVE_BENCH_GATEWAY_S simulated seconds
(default 20; the acceptance of the gateway issue is 60).
"""

from __future__ import annotations

import asyncio
import os
import socket
import threading
import time
from pathlib import Path

import numpy as np
import websockets
from rich.console import Console
from rich.table import Table

from bench.step_latency import StepLatency
from coopdrive.launch.ports import free_tcp_port
from coopdrive.launch.run import RunOptions, run_scenario

DURATION_ENV = "COOPDRIVE_BENCH_GATEWAY_S"
DEFAULT_DURATION_S = 20.0
CLIENTS = 50
CONNECT_RETRY_S = 0.2
GATEWAY_START_TIMEOUT_S = 30.0
RSS_SAMPLE_PERIOD_S = 0.5


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
    """CLIENTS WebSocket clients on /ws in their own event loop thread; client 0 never reads."""

    def __init__(self, port: int, count: int):
        self.url = f"ws://127.0.0.1:{port}/ws"
        self.count = count
        self.frames = 0
        self.connected = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=lambda: asyncio.run(self._main()), daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(10.0)

    async def _main(self) -> None:
        await asyncio.gather(*(self._client(i) for i in range(self.count)), return_exceptions=True)

    async def _client(self, index: int) -> None:
        while not self._stop.is_set():
            try:
                async with websockets.connect(self.url, max_queue=None if index else 1) as ws:
                    self.connected += 1
                    while not self._stop.is_set():
                        if index == 0:
                            await asyncio.sleep(CONNECT_RETRY_S)  # never reads: the server's sends back up
                            continue
                        try:
                            await asyncio.wait_for(ws.recv(), CONNECT_RETRY_S)
                            self.frames += 1
                        except asyncio.TimeoutError:
                            pass
                    return
            except (OSError, websockets.WebSocketException):
                await asyncio.sleep(CONNECT_RETRY_S)


def run(duration_s: float, clients: int):
    port = free_tcp_port()
    latency = StepLatency()
    rss: list[int] = []
    done = threading.Event()

    def watch() -> None:
        deadline = time.monotonic() + GATEWAY_START_TIMEOUT_S
        pid = None
        while pid is None and time.monotonic() < deadline and not done.is_set():
            pid = gateway_pid()
            time.sleep(0.05)
        if pid is None:
            return
        # RSS "start" is taken once the gateway serves, not while its interpreter is still importing.
        while not done.is_set() and time.monotonic() < deadline + GATEWAY_START_TIMEOUT_S:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1.0).close()
                break
            except OSError:
                time.sleep(0.1)
        ws = Clients(port, clients) if clients else None
        if ws is not None:
            ws.start()
        while not done.wait(RSS_SAMPLE_PERIOD_S):
            sample = rss_kib(pid)
            if sample is not None:
                rss.append(sample)
        if ws is not None:
            ws.stop()
            watch.connected, watch.frames = ws.connected, ws.frames

    watch.connected, watch.frames = 0, 0
    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    try:
        result = run_scenario(RunOptions(duration_s=duration_s, realtime=True, gateway_port=port,
                                         observer=latency.observe))
    finally:
        done.set()
        watcher.join(15.0)
    return result, latency.latencies_ms(), rss, watch.connected, watch.frames


def main() -> None:
    duration_s = float(os.environ.get(DURATION_ENV, DEFAULT_DURATION_S))
    table = Table(title=f"follow scenario, --realtime with the gateway, {duration_s:.0f} s simulated: "
                        f"/ws clients vs none (one client never reads)")
    for column in ("/ws clients", "connected", "frames read", "success", "sensor -> command p50 (ms)", "p99 (ms)",
                   "p50 ratio", "p99 ratio", "gateway RSS start (MiB)", "end (MiB)"):
        table.add_column(column, justify="right")
    baseline = None
    for clients in (0, CLIENTS):
        result, latencies_ms, rss, connected, frames = run(duration_s, clients)
        p50, p99 = (np.percentile(latencies_ms, q) for q in (50, 99)) if latencies_ms.size else (float("nan"),) * 2
        if baseline is None:
            baseline = (p50, p99)
        table.add_row(str(clients), str(connected), str(frames), str(result.success), f"{p50:.2f}", f"{p99:.2f}",
                      f"{p50 / baseline[0]:.2f}", f"{p99 / baseline[1]:.2f}",
                      f"{rss[0] / 1024:.1f}" if rss else "-", f"{rss[-1] / 1024:.1f}" if rss else "-")
    Console().print(table)


if __name__ == "__main__":
    main()
