"""run_batch: a sweep (batch.BatchOptions) on a Dask cluster, with a live progress bar and summary table."""

from __future__ import annotations

import tempfile
import time
from contextlib import nullcontext
from pathlib import Path

from rich.console import Console, Group
from rich.live import Live
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from coopdrive.launch.batch import BatchOptions, BatchSummary, RunOutcome, unfinished_line
from coopdrive.launch.sweep_task import SweepJob
from coopdrive.services.sim.scenario_config import ScenarioError


def sweep_jobs(options: BatchOptions) -> list[SweepJob]:
    """Every (scenario, fault variant, seed) once, in that order."""
    reports = options.out_dir is not None and options.reports
    return [SweepJob(options.run.model_copy(update={"scenario": scenario, "seed": seed, "extra_faults": faults}),
                     fault, report=reports)
            for scenario in dict.fromkeys(options.scenarios)
            for fault, faults in options.fault_variants.items()
            for seed in dict.fromkeys(options.seeds)]


def check_runs(options: BatchOptions) -> None:
    """Checks each (scenario, fault variant)'s run as its run will, so that a bad scenario, a fault naming a vehicle
    the scenario lacks or a bad --stacks stops the sweep before anything starts (ScenarioError, one line)."""
    from coopdrive.launch.run import checked_run

    for scenario in dict.fromkeys(options.scenarios):
        for fault, faults in options.fault_variants.items():
            run = options.run.model_copy(update={"scenario": scenario, "extra_faults": faults})
            with tempfile.TemporaryDirectory(prefix="coopdrive-check-") as folder:
                try:
                    checked_run(run, Path(folder))
                except ScenarioError as error:
                    # The scenario with the variant's faults is a file in the check's folder: name it alone.
                    message = str(error).replace(f"{folder}/", "")
                    raise ScenarioError(f"fault variant {fault!r}: {message}"
                                        if faults else message) from None


def time_left_s(limit_s: float | None, started_s: float) -> float | None:
    """What is left of a sweep's time limit, which counts from the sweep's start: starting a local cluster is time
    the sweep takes too (seconds on a busy machine, as CI's sweep beside the suite finds)."""
    if limit_s is None:
        return None
    return max(0.0, limit_s - (time.monotonic() - started_s))


def run_batch(options: BatchOptions, console: Console | None = None) -> BatchSummary:
    """Runs the sweep on options.cluster, or on a local cluster of options.workers processes. ScenarioError or
    SweepError, before anything runs, for a sweep that cannot start."""
    from coopdrive.launch.sweep_cluster import stream_runs, sweep_client
    from coopdrive.launch.sweep_output import (print_whole, retried_lines, run_line, summary_table, write_run,
                                               write_summary)

    started_s = time.monotonic()
    console = console or Console()
    check_runs(options)
    jobs = sweep_jobs(options)
    outcomes: list[RunOutcome] = []
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    progress = Progress(*columns, console=console)
    bar = progress.add_task("runs", total=len(jobs))
    # On a terminal a live bar and table; in a log a line per run as it finishes, and the table at the end.
    live = Live(progress, console=console, refresh_per_second=4) if console.is_terminal else None
    with live or nullcontext():
        def finished(outcome: RunOutcome, files: dict[str, bytes]) -> None:
            outcomes.append(outcome)
            if options.out_dir is not None:
                write_run(options.out_dir, outcome, files)
            if live is None:
                console.print(run_line(outcome, len(outcomes), len(jobs)))
                return
            retried = sum(o.retried for o in outcomes)
            progress.update(bar, advance=1, description=f"runs ({retried} retried)" if retried else "runs")
            live.update(Group(progress, summary_table(BatchSummary(outcomes))))

        with sweep_client(options.cluster, options.workers) as client:
            unfinished, end = stream_runs(client, jobs, finished, time_left_s(options.time_limit_s, started_s))
    if live is None:
        print_whole(console, summary_table(BatchSummary(outcomes)))
    summary = BatchSummary(outcomes, sorted(job.label for job in unfinished), end)
    if unfinished:
        console.print(f"[yellow]{unfinished_line(summary, options.time_limit_s)}[/]")
    for line in retried_lines(summary):
        console.print(line)
    if options.out_dir is not None:
        write_summary(summary, options.out_dir)
    return summary
