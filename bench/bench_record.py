"""What recording costs a multi-stack run: `string --stacks 8` in lockstep with `--record` against the same run
without, turn about (unrecorded, recorded, three times), so a load that comes and goes weighs on both alike; the
turns' own ratios give each ratio its interval (bench/turn_spread.py: two quiet runs of one commit moved both ratios
by 10-11 %).

Each process of a recorded run spools what it publishes, and the launcher (this process) merges the spools into the
MCAP as the run goes, drawing the Foxglove channels as it writes. Its CPU is this process's (every thread, Zenoh's
too) from the command to its return, the merge included; the ratio column is the recorded run's real-time factor
over the unrecorded one's (below 1: the cost while it runs), and the command's wall time, whose ratio is the other
figure, adds what the merge has left when the run ends. The merge moved into the run on 2026-12-07: the
real-time factor ratio fell from 0.90-1.03 to 0.80-0.90, and the command's stayed about where it was (1.10-1.26
in three runs, 1.20 in one run before).
BENCH_RECORD_STACKS and BENCH_RECORD_DURATION_S set the stacks (default 8) and the simulated seconds (default 10).
"""

from __future__ import annotations

import os
import statistics
import tempfile
import time
from pathlib import Path

from rich.console import Console
from rich.table import Table

from bench.failure import require_success
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_spread import turn_ratio_spread
from coopdrive.launch.run import RunOptions, run_scenario

SCENARIO = "string"
STACKS = int(os.environ.get("BENCH_RECORD_STACKS", sized(8, 2)))
DURATION_S = float(os.environ.get("BENCH_RECORD_DURATION_S", sized(10.0, 1.0)))
ROUNDS = sized(3, 1)


def run(record: Path | None) -> tuple[float, float, float]:
    """(real-time factor, the launcher's CPU seconds per simulated second, the command's wall seconds) of one run."""
    cpu_before_s, started_s = time.process_time(), time.monotonic()
    result = run_scenario(RunOptions(scenario=SCENARIO, stacks=STACKS, duration_s=DURATION_S, record=record))
    require_success(result, f"the {'recorded' if record else 'unrecorded'} run")
    launcher_cpu_s = time.process_time() - cpu_before_s
    return result.sim_time_s / max(result.wall_time_s, 1e-9), launcher_cpu_s / DURATION_S, time.monotonic() - started_s


def main() -> list[Figure]:
    factors: dict[bool, list[float]] = {False: [], True: []}
    launcher_cpu: dict[bool, list[float]] = {False: [], True: []}
    command_s: dict[bool, list[float]] = {False: [], True: []}
    with tempfile.TemporaryDirectory() as folder:
        for round_index in range(ROUNDS):
            for recorded in (False, True):
                record = Path(folder) / f"run-{round_index}.mcap" if recorded else None
                factor, cpu, wall_s = run(record)
                factors[recorded].append(factor)
                launcher_cpu[recorded].append(cpu)
                command_s[recorded].append(wall_s)
    table = Table(title=f"{SCENARIO} --stacks {STACKS}, {DURATION_S:.0f} s simulated, lockstep: what --record costs "
                        f"(mean of {ROUNDS} runs each, turn about)")
    for column in ("run", "sim_time_s / wall_time_s", "ratio to unrecorded", "launcher CPU per simulated s",
                   "command wall s"):
        table.add_column(column, justify="right")
    unrecorded = statistics.mean(factors[False])
    figures = []
    for recorded, name in ((False, "unrecorded"), (True, "--record")):
        factor, cpu_ms = statistics.mean(factors[recorded]), 1e3 * statistics.mean(launcher_cpu[recorded])
        table.add_row(name, f"{factor:.2f}", f"{factor / unrecorded:.2f}", f"{cpu_ms:.0f} ms",
                      f"{statistics.mean(command_s[recorded]):.1f}")
        figures += [Figure(f"{name}: real-time factor", factor, Unit.REALTIME_FACTOR),
                    Figure(f"{name}: launcher CPU", cpu_ms, Unit.MS_PER_SIMULATED_S),
                    Figure(f"{name}: command", statistics.mean(command_s[recorded]), Unit.S)]
    Console().print(table)
    return figures + [ratio("--record: real-time factor to unrecorded", statistics.mean(factors[True]) / unrecorded,
                            "unrecorded: real-time factor", Better.HIGHER,
                            spread=turn_ratio_spread(factors[True], factors[False])),
                      ratio("--record: command to unrecorded",
                            statistics.mean(command_s[True]) / statistics.mean(command_s[False]),
                            "unrecorded: command", Better.LOWER,
                            spread=turn_ratio_spread(command_s[True], command_s[False]))]


if __name__ == "__main__":
    main()
