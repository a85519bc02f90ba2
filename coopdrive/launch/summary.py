"""The end-of-run summary: a table for people, JSON for scripts."""

from __future__ import annotations

from pathlib import Path

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from coopdrive.judging.counts import COUNT_METRICS
from coopdrive.launch.lockstep_give_ups import GIVE_UP_MEANING
from coopdrive.runtime.barrier import MESSAGES_GIVEN_UP_COUNTER
from coopdrive.v1 import sim_pb2

# The summary's keys read off the wall clock: they differ between two runs of one seed, the others may not.
WALL_CLOCK_KEYS = ("wall_time_s", "realtime_factor", "startup_time_s", "shutdown_time_s")


def summary_dict(result: sim_pb2.RunResult) -> dict:
    summary = {
        "scenario": result.scenario,
        "seed": result.seed,
        "success": result.success,
        "failure_reason": result.failure_reason,
        "sim_time_s": round(result.sim_time_s, 6),
        "wall_time_s": round(result.wall_time_s, 3),
        "realtime_factor": round(result.sim_time_s / result.wall_time_s, 2) if result.wall_time_s > 0 else 0.0,
        # Besides the stepping: from the command's start to step 0, and from the result to the last process gone.
        "startup_time_s": round(result.startup_time_s, 3),
        "shutdown_time_s": round(result.shutdown_time_s, 3),
    }
    for key, value in sorted(result.metrics.items()):
        summary[key] = int(value) if key in COUNT_METRICS else round(value, 6)
    summary.setdefault("collisions", 0)
    summary.setdefault("min_gap_m", -1.0)
    if result.fault_reactions:
        summary["fault_reactions"] = list(result.fault_reactions)
    return summary


def print_summary(result: sim_pb2.RunResult, recording: Path | None = None, label: str = "") -> None:
    summary = summary_dict(result)
    table = Table(title=f"coopdrive run {result.scenario} (seed {result.seed}){label}")
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in summary.items():
        # The title names the run; the verdict line says why it failed, the lines under it what the stacks did
        # about the faults.
        if key in ("scenario", "seed", "failure_reason", "fault_reactions"):
            continue
        table.add_row(key, f"{value:.3f}" if isinstance(value, float) else str(value))
    # No automatic highlighting: rich compiles its repr highlighter's regexes on first use, about 0.3 s of a short run.
    console = Console(highlight=False)
    console.print(table)
    verdict = "[bold green]PASS[/]" if result.success else f"[bold red]FAIL[/]: {result.failure_reason}"
    console.print(verdict)
    print_fault_reactions(console, result)
    warn_if_not_deterministic(console, summary)
    if recording is not None:
        console.print(f"recording: {recording}")


def print_fault_reactions(console: Console, result: sim_pb2.RunResult) -> None:
    """Under the verdict, what the stacks did about each fault the judge follows, a line each."""
    for reaction in result.fault_reactions:
        console.print(f"  {escape(reaction)}")


def warn_if_not_deterministic(console: Console, summary: dict) -> None:
    give_ups = summary.get(MESSAGES_GIVEN_UP_COUNTER, 0)
    if give_ups:
        console.print(f"[bold yellow]not deterministic[/]: {give_ups} times {GIVE_UP_MEANING} (an overloaded host?)")
