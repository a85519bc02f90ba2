"""Where a run's CPU goes, handler by handler: the ledgers a run writes with COOPDRIVE_HANDLER_CPU_DIR, added up.

    COOPDRIVE_HANDLER_CPU_DIR=out/cpu coopdrive run merge --processes one --duration 30
    .venv/bin/python -m bench.profile_handlers out/cpu [--most 25] [--simulated-s 30]

Each service of each vehicle writes its ledger (coopdrive/runtime/handler_ledger.py); the rows of a service's
handler on every vehicle are summed into one (scene's v2x/cam on all stacks, say). A service's "runtime" row is
its worker's CPU less its handlers': taking events off the queue and decoding their messages, the lockstep
barrier, and sending what the step published (in lockstep a step's messages go out with its marker). The share
is of every service's worker CPU; Zenoh's native threads and the launcher are not in it (bench.profile_run
reads those from /proc).
"""

from __future__ import annotations

import argparse
import csv
import sys
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.table import Table

from coopdrive.runtime.handler_ledger import HANDLER_CPU_SUFFIX, WORKER_ROW

# A table written to a file or a pipe is read whole: rich would fold it to 80 columns.
PIPED_WIDTH = 160
RUNTIME_ROW = "runtime: events, barrier, the step's sends"


@dataclass
class HandlerRow:
    service: str
    handler: str
    calls: int
    cpu_s: float
    # The longest single call on any vehicle; 0 for a runtime row.
    longest_call_cpu_s: float = 0.0


def read_ledgers(folder: Path) -> list[HandlerRow]:
    """Every handler's row summed over the vehicles, and each service's runtime row, most CPU first."""
    calls: dict[tuple[str, str], int] = defaultdict(int)
    cpu_s: dict[tuple[str, str], float] = defaultdict(float)
    longest_s: dict[tuple[str, str], float] = defaultdict(float)
    for path in sorted(folder.glob(f"*{HANDLER_CPU_SUFFIX}")):
        service = path.name.removesuffix(HANDLER_CPU_SUFFIX).rsplit("-", 1)[-1]
        with path.open(newline="") as ledger:
            for row in csv.DictReader(ledger):
                spent_s = float(row["cpu_s"])
                if row["kind"] == WORKER_ROW:
                    cpu_s[service, RUNTIME_ROW] += spent_s
                    continue
                key = (service, f"{row['kind']} {row['name']}")
                calls[key] += int(row["calls"])
                cpu_s[key] += spent_s
                longest_s[key] = max(longest_s[key], float(row["longest_call_cpu_s"]))
                cpu_s[service, RUNTIME_ROW] -= spent_s
    rows = [HandlerRow(service, handler, calls.get((service, handler), 0), spent_s,
                       longest_s.get((service, handler), 0.0)) for (service, handler), spent_s in cpu_s.items()]
    return sorted(rows, key=lambda row: -row.cpu_s)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path, help="the run's COOPDRIVE_HANDLER_CPU_DIR")
    parser.add_argument("--most", type=int, default=25, help="rows to print (default 25)")
    parser.add_argument("--simulated-s", type=float, help="the run's simulated seconds: adds ms per simulated s")
    args = parser.parse_args(argv)
    rows = read_ledgers(args.folder)
    if not rows:
        parser.error(f"{args.folder} holds no *{HANDLER_CPU_SUFFIX}: was COOPDRIVE_HANDLER_CPU_DIR set for the run?")
    total_s = sum(row.cpu_s for row in rows)
    table = Table(title=f"{args.folder}: every service's worker CPU, {total_s:.2f} s, by handler")
    for column in ("service", "handler", "calls", "CPU s", "share", "us per call", "longest call ms") + (
            ("ms per simulated s",) if args.simulated_s else ()):
        table.add_column(column, justify="left" if column in ("service", "handler") else "right")
    for row in rows[:args.most]:
        per_call = f"{1e6 * row.cpu_s / row.calls:.0f}" if row.calls else "-"
        longest = f"{1e3 * row.longest_call_cpu_s:.2f}" if row.calls else "-"
        cells = [row.service, row.handler, str(row.calls or "-"), f"{row.cpu_s:.2f}",
                 f"{100 * row.cpu_s / total_s:.1f} %", per_call, longest]
        if args.simulated_s:
            cells.append(f"{1e3 * row.cpu_s / args.simulated_s:.0f}")
        table.add_row(*cells)
    Console(width=None if sys.stdout.isatty() else PIPED_WIDTH).print(table)
    if len(rows) > args.most:
        print(f"({len(rows) - args.most} more rows, {sum(r.cpu_s for r in rows[args.most:]):.2f} s)")


if __name__ == "__main__":
    main()
