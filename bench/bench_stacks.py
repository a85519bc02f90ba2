"""Real-time factor of 1, 4 and 8 full stacks in lockstep (the string scenario), and where the time goes.

Each stack runs as one process (`coopdrive group`), its services on one shared worker thread; the last rows run
8 stacks with a thread per service, as before the shared worker, and the simulator and 8 stacks in one process
(`--processes one`), its messages to itself handed over by the bus (coopdrive/bus/local_delivery.py) and, turn
about, through Zenoh as before, in the same bench. The per-service figures are the CPU seconds of each service's own handling
(its handlers and triggers), from the last diagnostics every service published.
BENCH_STACKS_DURATION_S sets the simulated seconds per run (default 10).
"""

from __future__ import annotations

import os
from collections import defaultdict

from rich.console import Console
from rich.table import Table

from bench import baselines
from bench.sizes import sized
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run import RunOptions, run_scenario

SCENARIO = "string"
STACK_COUNTS = sized((1, 4, 8), (1, 2))
DURATION_S = float(os.environ.get("BENCH_STACKS_DURATION_S", sized(10.0, 1.0)))


def run(stacks: int, thread_per_service: bool = False, processes: ProcessLayout = ProcessLayout.VEHICLE,
        local_by_zenoh: bool = False) -> tuple[float, dict[str, dict[str, float]]]:
    """`thread_per_service`: each stack's group gives each service its own thread, as before the shared worker;
    `local_by_zenoh`: a process's messages to its own services go through Zenoh, as before the bus's own delivery."""
    worker_cpu_s: dict[str, dict[str, float]] = defaultdict(dict)

    def observe(key: str, message) -> None:
        parts = key.split("/")
        if len(parts) == 4 and parts[2] == "diagnostics" and "worker_cpu_s" in message.counters:
            worker_cpu_s[parts[1]][parts[3]] = message.counters["worker_cpu_s"]

    with baselines.thread_per_service(thread_per_service), baselines.local_by_zenoh(local_by_zenoh):
        result = run_scenario(RunOptions(scenario=SCENARIO, stacks=stacks, duration_s=DURATION_S, observer=observe,
                                         processes=processes))
    return result.sim_time_s / max(result.wall_time_s, 1e-9), worker_cpu_s


def main() -> None:
    console = Console(width=max(Console().width, 110))
    summary = Table(title=f"{SCENARIO}: lockstep, one process per stack, {DURATION_S:.0f} s simulated")
    for column in ("stacks", "sim_time_s / wall_time_s", "ratio to 1 stack", "stack CPU per simulated s"):
        summary.add_column(column, justify="right")
    baseline = None
    breakdown = None
    for stacks in STACK_COUNTS:
        factor, cpu = run(stacks)
        baseline = baseline or factor
        stack_cpu_s = sum(sum(services.values()) for vehicle, services in cpu.items() if vehicle != "world")
        summary.add_row(str(stacks), f"{factor:.2f}", f"{factor / baseline:.2f}", f"{stack_cpu_s / DURATION_S:.2f} s")
        breakdown = cpu
    factor, _ = run(STACK_COUNTS[-1], thread_per_service=True)
    summary.add_row(f"{STACK_COUNTS[-1]}, a thread per service (before)", f"{factor:.2f}", f"{factor / baseline:.2f}",
                    "")
    # Turn about, so a load that comes and goes weighs on both.
    for local_by_zenoh in (True, False):
        factor, _ = run(STACK_COUNTS[-1], processes=ProcessLayout.ONE, local_by_zenoh=local_by_zenoh)
        delivered = "its messages through Zenoh (before)" if local_by_zenoh else "handed over by the bus"
        summary.add_row(f"{STACK_COUNTS[-1]}, all in one process, {delivered}", f"{factor:.2f}",
                        f"{factor / baseline:.2f}", "")
    console.print(summary)
    if breakdown:
        services = sorted({s for per_vehicle in breakdown.values() for s in per_vehicle})
        table = Table(title=f"where the time goes, {STACK_COUNTS[-1]} stacks: worker CPU per simulated second (ms)")
        table.add_column("vehicle")
        for service in services:
            table.add_column(service, justify="right")
        for vehicle in sorted(breakdown):
            table.add_row(vehicle, *(f"{1e3 * breakdown[vehicle][s] / DURATION_S:.0f}" if s in breakdown[vehicle]
                                     else "" for s in services))
        console.print(table)


if __name__ == "__main__":
    main()
