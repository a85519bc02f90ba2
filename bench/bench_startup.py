"""The whole `coopdrive run follow` command as its user waits for it, start to prompt, in each process layout:
5 and 60 simulated seconds, with the summary's own start-up, stepping and shut-down times.

One process per service (`--processes service`) is the layout every single-stack run had before issue 27; the
default is one process per vehicle. Issue 27 asks for `run follow --duration 5` under 3 s and the 60 s run
under 5 s; before it, the 60 s run took 30 s on a quiet 2-core machine.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

from rich.console import Console
from rich.table import Table

from bench.sizes import sized

LAYOUTS = ("service", "vehicle")
DURATIONS_S = sized((5.0, 60.0), (1.0, 2.0))


def command_time(duration_s: float, layout: str) -> tuple[float, dict]:
    started = time.monotonic()
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--json", "--duration",
                                str(duration_s), "--processes", layout], capture_output=True, text=True, check=True)
    return time.monotonic() - started, json.loads(completed.stdout)


def main() -> None:
    table = Table(title="coopdrive run follow: the command, start to prompt (s)")
    for column in ("simulated s", "processes", "command", "start-up", "stepping", "shut-down", "real-time factor"):
        table.add_column(column, justify="right")
    for duration_s in DURATIONS_S:
        for layout in LAYOUTS:
            total_s, summary = command_time(duration_s, layout)
            table.add_row(f"{duration_s:.0f}", f"one per {layout}", f"{total_s:.2f}",
                          f"{summary['startup_time_s']:.2f}", f"{summary['wall_time_s']:.2f}",
                          f"{summary['shutdown_time_s']:.2f}", f"{summary['realtime_factor']:.1f}")
    Console().print(table)


if __name__ == "__main__":
    main()
