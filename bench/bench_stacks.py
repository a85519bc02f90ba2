"""Real-time factor of 1, 4 and 8 full stacks in lockstep (the string scenario), and where the time goes.

Each stack runs as one process (`coopdrive group`), its services on one shared worker thread; the last rows run
8 stacks with a thread per service, as before the shared worker, and the simulator and 8 stacks in one process
(`--processes one`), its messages to itself handed over by the bus (coopdrive/bus/local_delivery.py) and, turn
about, through Zenoh as before, in the same bench. These last comparisons and 8 stacks' to 1 stack's run in TURNS
rounds of shorter runs, each round all five (8 stacks as the rows above run them, a thread per service, through
Zenoh, by the bus, and 1 stack), so that each ratio gets its interval from its rounds (bench/turn_spread.py): measured once each, two quiet runs of one commit
moved them by 10-14 %. The per-service figures are the CPU seconds of each service's own handling
(its handlers and triggers), from the last diagnostics every service published.
BENCH_STACKS_DURATION_S sets the simulated seconds per run (default 10).
"""

from __future__ import annotations

import os
import statistics
from collections import defaultdict

from rich.console import Console
from rich.table import Table

from bench import baselines
from bench.failure import require_success
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_about import turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run import RunOptions, run_scenario

SCENARIO = "string"
STACK_COUNTS = sized((1, 4, 8), (1, 2))
DURATION_S = float(os.environ.get("BENCH_STACKS_DURATION_S", sized(10.0, 1.0)))
# The rounds of the comparisons of 8 stacks, and their runs' simulated seconds: a real-time factor counts the
# stepping only, not the start, so half the rows' length measures the same thing in half the time.
TURNS = sized(3, 1)
TURN_DURATION_S = DURATION_S / 2


def run(stacks: int, thread_per_service: bool = False, processes: ProcessLayout = ProcessLayout.VEHICLE,
        local_by_zenoh: bool = False, duration_s: float = DURATION_S) -> tuple[float, dict[str, dict[str, float]]]:
    """`thread_per_service`: each stack's group gives each service its own thread, as before the shared worker;
    `local_by_zenoh`: a process's messages to its own services go through Zenoh, as before the bus's own delivery."""
    worker_cpu_s: dict[str, dict[str, float]] = defaultdict(dict)

    def observe(key: str, message) -> None:
        parts = key.split("/")
        if len(parts) == 4 and parts[2] == "diagnostics" and "worker_cpu_s" in message.counters:
            worker_cpu_s[parts[1]][parts[3]] = message.counters["worker_cpu_s"]

    with baselines.thread_per_service(thread_per_service), baselines.local_by_zenoh(local_by_zenoh):
        result = run_scenario(RunOptions(scenario=SCENARIO, stacks=stacks, duration_s=duration_s, observer=observe,
                                         processes=processes))
    require_success(result, f"the run of {stacks} stacks ({processes.value})")
    return result.sim_time_s / max(result.wall_time_s, 1e-9), worker_cpu_s


def main() -> list[Figure]:
    console = Console(width=max(Console().width, 110))
    summary = Table(title=f"{SCENARIO}: lockstep, one process per stack, {DURATION_S:.0f} s simulated")
    for column in ("stacks", "sim_time_s / wall_time_s", "ratio to 1 stack", "stack CPU per simulated s"):
        summary.add_column(column, justify="right")
    breakdown = None
    most, factors = STACK_COUNTS[-1], {}
    for stacks in STACK_COUNTS:
        factors[f"{stacks} stacks"], cpu = run(stacks)
        stack_cpu_s = sum(sum(services.values()) for vehicle, services in cpu.items() if vehicle != "world")
        summary.add_row(str(stacks), *ratio_cells(factors, f"{stacks} stacks"), f"{stack_cpu_s / DURATION_S:.2f} s")
        breakdown = cpu
    threads, by_zenoh, by_bus = (f"{most}, a thread per service (before)", f"{most}, all in one process, its "
                                 "messages through Zenoh (before)", f"{most}, all in one process, handed over by the bus")
    # Turn about, so a load that comes and goes weighs on all five.
    most_turns, threads_turns, zenoh_turns, bus_turns, one_turns = turns([
        lambda: run(most, duration_s=TURN_DURATION_S)[0],
        lambda: run(most, thread_per_service=True, duration_s=TURN_DURATION_S)[0],
        lambda: run(most, processes=ProcessLayout.ONE, local_by_zenoh=True, duration_s=TURN_DURATION_S)[0],
        lambda: run(most, processes=ProcessLayout.ONE, local_by_zenoh=False, duration_s=TURN_DURATION_S)[0],
        lambda: run(1, duration_s=TURN_DURATION_S)[0]], TURNS)
    for label, measured in ((threads, threads_turns), (by_zenoh, zenoh_turns), (by_bus, bus_turns)):
        factors[label] = statistics.fmean(measured)
        summary.add_row(label, *ratio_cells(factors, label), "")
    console.print(summary)
    print_breakdown(console, breakdown)
    return [Figure(f"{label}: real-time factor", factor, Unit.REALTIME_FACTOR) for label, factor in factors.items()] + [
        ratio(f"{most} stacks: real-time factor to a thread per service",
              statistics.fmean(most_turns) / factors[threads], f"{threads}: real-time factor", Better.HIGHER,
              spread=turn_ratio_spread(most_turns, threads_turns)),
        ratio(f"{most} in one process: the bus's hand-over to Zenoh's", factors[by_bus] / factors[by_zenoh],
              f"{by_zenoh}: real-time factor", Better.HIGHER, spread=turn_ratio_spread(bus_turns, zenoh_turns)),
        ratio(f"{most} stacks: real-time factor to 1 stack's", statistics.fmean(most_turns) / statistics.fmean(one_turns),
              "1 stacks: real-time factor", Better.HIGHER, spread=turn_ratio_spread(most_turns, one_turns))]


def ratio_cells(factors: dict[str, float], label: str) -> tuple[str, str]:
    """The real-time factor of `label` and its ratio to the first run's (1 stack)."""
    first = next(iter(factors.values()))
    return f"{factors[label]:.2f}", f"{factors[label] / first:.2f}"


def print_breakdown(console: Console, breakdown: dict[str, dict[str, float]] | None) -> None:
    if not breakdown:
        return
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
