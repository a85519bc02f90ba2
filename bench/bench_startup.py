"""The whole `coopdrive run follow` command as its user waits for it, start to prompt, in each process layout:
5 and 60 simulated seconds, with the summary's own start-up, stepping and shut-down times. Then an 8-stack string
run's command with its services forked from the preloaded server (the default) against the same run with each
service a new interpreter (COOPDRIVE_NEW_INTERPRETERS=1, as before), turn about.

One process per service (`--processes service`) is the layout every single-stack run had before issue 27; the
default is one process per vehicle. Issue 27 asks for `run follow --duration 5` under 3 s and the 60 s run
under 5 s; before it, the 60 s run took 30 s on a quiet 2-core machine.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time

from rich.console import Console
from rich.table import Table

from bench.failure import BenchFailed
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_spread import turn_ratio_spread

from coopdrive.launch.processes import NEW_INTERPRETERS_VARIABLE

# The quick size starts the default layout only: each command is a whole run.
LAYOUTS = sized(("service", "vehicle"), ("vehicle",))
DURATIONS_S = sized((5.0, 60.0), (1.0,))
STACKS = sized(8, 1)
STACKS_DURATION_S = sized(5.0, 0.5)
# Rounds of the two 8-stack commands, turn about: each round gives one ratio, and their spread its interval.
ROUNDS = sized(3, 1)


def command_time(arguments: list[str], new_interpreters: bool = False) -> tuple[float, dict]:
    environment = {**os.environ, NEW_INTERPRETERS_VARIABLE: "1" if new_interpreters else "0"}
    started = time.monotonic()
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", *arguments, "--json"],
                               capture_output=True, text=True, env=environment)
    if completed.returncode != 0:
        said = (completed.stderr.strip() or "nothing").splitlines()[-1]
        raise BenchFailed(f"coopdrive run {' '.join(arguments)} exited {completed.returncode}: {said}")
    return time.monotonic() - started, json.loads(completed.stdout)


def forked_against_new_interpreters() -> list[Figure]:
    arguments = ["string", "--stacks", str(STACKS), "--duration", str(STACKS_DURATION_S)]
    times: dict[bool, list[tuple[float, float, float]]] = {False: [], True: []}
    for _ in range(ROUNDS):
        for new_interpreters in (True, False):
            total_s, summary = command_time(arguments, new_interpreters)
            times[new_interpreters].append((total_s, summary["startup_time_s"], summary["shutdown_time_s"]))
    table = Table(title=f"coopdrive run {' '.join(arguments)}: services forked or started as new interpreters "
                        f"(mean of {ROUNDS}, turn about; s)")
    for column in ("services", "command", "start-up", "shut-down", "command / new interpreters'"):
        table.add_column(column, justify="right")
    baseline_s = statistics.mean(total for total, _, _ in times[True])
    figures = []
    for new_interpreters, name in ((True, "new interpreters"), (False, "forked")):
        total_s, startup_s, shutdown_s = (statistics.mean(column) for column in zip(*times[new_interpreters]))
        table.add_row(name, f"{total_s:.2f}", f"{startup_s:.2f}", f"{shutdown_s:.2f}", f"{total_s / baseline_s:.2f}")
        figures += [Figure(f"{STACKS} stacks, {name}: command", total_s, Unit.S),
                    Figure(f"{STACKS} stacks, {name}: start-up", startup_s, Unit.S)]
    Console().print(table)
    forked_turns_s, new_turns_s = ([total for total, _, _ in times[new]] for new in (False, True))
    return figures + [ratio(f"{STACKS} stacks: forked command to new interpreters'", figures[2].value / baseline_s,
                            f"{STACKS} stacks, new interpreters: command", Better.LOWER,
                            spread=turn_ratio_spread(forked_turns_s, new_turns_s))]


def main() -> list[Figure]:
    table = Table(title="coopdrive run follow: the command, start to prompt (s)")
    for column in ("simulated s", "processes", "command", "start-up", "stepping", "shut-down", "real-time factor"):
        table.add_column(column, justify="right")
    figures = []
    for duration_s in DURATIONS_S:
        for layout in LAYOUTS:
            total_s, summary = command_time(["follow", "--duration", str(duration_s), "--processes", layout])
            table.add_row(f"{duration_s:.0f}", f"one per {layout}", f"{total_s:.2f}",
                          f"{summary['startup_time_s']:.2f}", f"{summary['wall_time_s']:.2f}",
                          f"{summary['shutdown_time_s']:.2f}", f"{summary['realtime_factor']:.1f}")
            run = f"follow {duration_s:g} s, one per {layout}"
            figures += [Figure(f"{run}: command", total_s, Unit.S),
                        Figure(f"{run}: start-up", summary["startup_time_s"], Unit.S)]
    Console().print(table)
    return figures + forked_against_new_interpreters()


if __name__ == "__main__":
    main()
