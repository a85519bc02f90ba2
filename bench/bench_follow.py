"""The follow loop: real-time factor in lockstep, and sensor-sample-to-actuation-command latency.

Latency is measured on the wall clock at the run's hub: from the arrival of the simulator's
clock message that closes step k (its sensor samples went out just before it) to the arrival of
the actuation command computed in that step.
"""

from __future__ import annotations

import threading
import time

import numpy as np
from rich.console import Console
from rich.table import Table

from coopdrive.launch.run import RunOptions, run_scenario

DURATION_S = 60.0
REQUIRED_REALTIME_FACTOR = 5.0


def main() -> None:
    clock_arrivals: dict[float, float] = {}
    command_arrivals: dict[float, float] = {}
    lock = threading.Lock()

    def observe(key: str, message) -> None:
        now = time.perf_counter()
        with lock:
            if key.endswith("world/clock"):
                clock_arrivals[round(message.time_s, 6)] = now
            elif key.endswith("ego/actuation/command"):
                command_arrivals[round(message.header.sent_time_s, 6)] = now

    result = run_scenario(RunOptions(duration_s=DURATION_S, observer=observe))
    latencies_ms = np.array([1e3 * (command_arrivals[t] - clock_arrivals[t])
                             for t in command_arrivals if t in clock_arrivals and command_arrivals[t] >= clock_arrivals[t]])
    factor = result.sim_time_s / result.wall_time_s
    table = Table(title=f"follow scenario, lockstep, {DURATION_S:.0f} s simulated")
    table.add_column("figure")
    table.add_column("value", justify="right")
    table.add_row("success", str(result.success))
    table.add_row("sim_time_s / wall_time_s", f"{factor:.2f} (required >= {REQUIRED_REALTIME_FACTOR})")
    table.add_row("steps per wall second", f"{result.sim_time_s / 0.01 / result.wall_time_s:.0f}")
    if latencies_ms.size:
        table.add_row("sensor -> actuation command p50 (ms)", f"{np.percentile(latencies_ms, 50):.2f}")
        table.add_row("sensor -> actuation command p99 (ms)", f"{np.percentile(latencies_ms, 99):.2f}")
    Console().print(table)


if __name__ == "__main__":
    main()
