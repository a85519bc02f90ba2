"""Batch runs (sweeps): every (scenario, fault variant, seed) on a Dask cluster, a live progress bar and
summary table, and the summary files.

`coopdrive run all --seeds 1-20` and `coopdrive run merge --seeds 1-5 --faults FILE --cluster ADDRESS` come here.
Each run is an ordinary lockstep run on a worker (so the same seed gives the same metrics as a single run); with
--out each run's folder <out>/<scenario>/<fault>/seed-<n>/ holds metrics.json and the run's report (report/), and
the sweep writes summary.json, summary.csv and pass_table.md. sweep_cluster.py is the Dask side.
"""

from __future__ import annotations

import enum
import tempfile
import time
from contextlib import nullcontext
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from rich.console import Console, Group
from rich.live import Live
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.sweep_faults import NO_FAULTS
from coopdrive.services.sim.scenario_config import SCENARIO_PACKAGE, ScenarioError

if TYPE_CHECKING:
    from coopdrive.launch.sweep_task import SweepJob


@dataclass
class BatchOptions:
    scenarios: list[str]
    seeds: list[int]
    stacks: int | None = None
    workers: int = 2
    out_dir: Path | None = None
    # With out_dir: each run's report (plots, index.html and its recording) beside its metrics.json. False: the
    # metrics and summaries only, for a sweep that is judged by its pass table alone (CI's).
    reports: bool = True
    duration_s: float | None = None
    # V2X security of every stack in every run (a SecurityMode value), as `coopdrive run --security`.
    security: str | None = None
    # The world every run is in, as `coopdrive run --world`.
    world: str = "real"
    # How each run's services are spread over processes, as `coopdrive run --processes`. One process per run:
    # the sweep's runs already fill the cores, and a run in one process spends 20-30 % less CPU than one spread
    # over a process per vehicle (docs/performance.md).
    processes: ProcessLayout = ProcessLayout.ONE
    # Every stack's cooperative law in every run (a CaccLaw value), as `coopdrive run --cacc-law`; None: ours.
    cacc_law: str | None = None
    # Fault variant name -> the faults it adds to every scenario (sweep_faults.py); each is a sweep dimension.
    fault_variants: dict[str, tuple[dict, ...]] = field(default_factory=lambda: {NO_FAULTS: ()})
    # A running Dask scheduler's address (tcp://host:8786); None: a local cluster of `workers` processes.
    cluster: str | None = None
    # The sweep stops this many seconds after it started (--time-limit): runs not finished by then are
    # cancelled and listed as not finished. None: no limit.
    time_limit_s: float | None = None


@dataclass
class RunOutcome:
    scenario: str
    seed: int
    success: bool
    failure_reason: str
    wall_time_s: float = 0.0
    metrics: dict[str, float] = field(default_factory=dict)
    fault: str = NO_FAULTS
    # A worker died while running it, and another ran it again; lost_workers are the ones that died.
    retried: bool = False
    lost_workers: list[str] = field(default_factory=list)

    @property
    def label(self) -> str:
        return run_label(self.scenario, self.fault, self.seed)


def run_label(scenario: str, fault: str, seed: int) -> str:
    """How a sweep names one of its runs, in its task keys and in what it prints."""
    return f"{scenario}/{fault}/seed-{seed}"


class SweepEnd(enum.Enum):
    """How a sweep ended: every run finished, or it was stopped with runs not finished."""

    COMPLETE = "complete"
    INTERRUPTED = "interrupted"  # Ctrl-C
    TIME_LIMIT = "time limit"  # BatchOptions.time_limit_s


@dataclass
class BatchSummary:
    outcomes: list[RunOutcome]
    # The labels of runs that never ended, and why the sweep stopped before they did.
    unfinished: list[str] = field(default_factory=list)
    end: SweepEnd = SweepEnd.COMPLETE

    @property
    def all_passed(self) -> bool:
        return bool(self.outcomes) and not self.unfinished and all(o.success for o in self.outcomes)

    def in_order(self) -> list[RunOutcome]:
        return sorted(self.outcomes, key=lambda o: (o.scenario, o.fault, o.seed))

    def by_case(self) -> dict[tuple[str, str], list[RunOutcome]]:
        """(scenario, fault variant) -> its runs, by seed."""
        grouped: dict[tuple[str, str], list[RunOutcome]] = {}
        for outcome in self.in_order():
            grouped.setdefault((outcome.scenario, outcome.fault), []).append(outcome)
        return grouped


def unfinished_line(summary: BatchSummary, time_limit_s: float | None) -> str:
    """Why the sweep stopped early and which runs it left, in one line."""
    why = f"time limit of {time_limit_s:g} s" if summary.end is SweepEnd.TIME_LIMIT else summary.end.value
    return f"{why}: {len(summary.unfinished)} run(s) not finished: {', '.join(summary.unfinished)}"


def parse_seeds(text: str) -> list[int]:
    """"1-20", "3" or "1,4,7-9" -> the seeds in order; ValueError names the part that is not one."""
    seeds: list[int] = []
    for part in text.split(","):
        part = part.strip()
        low, dash, high = part.partition("-")
        try:
            first, last = (int(low), int(high)) if dash else (int(part), int(part))
        except ValueError:
            raise ValueError(f"{part!r} is not a seed or a range A-B") from None
        if first < 0 or last < first:
            raise ValueError(f"{part!r} is not a range of non-negative seeds A-B with A <= B")
        seeds.extend(range(first, last + 1))
    return list(dict.fromkeys(seeds))


def scenario_names() -> list[str]:
    """Every scenario `run all` runs: each packaged YAML file."""
    names = set()
    for entry in resources.files(SCENARIO_PACKAGE).iterdir():
        if entry.name.endswith((".yaml", ".yml")):
            names.add(entry.name.rsplit(".", 1)[0])
    return sorted(names)


def sweep_jobs(options: BatchOptions) -> list[SweepJob]:
    """Every (scenario, fault variant, seed) once, in that order."""
    from coopdrive.launch.sweep_task import SweepJob  # it imports this module's RunOutcome

    reports = options.out_dir is not None and options.reports
    return [SweepJob(scenario, fault, seed, faults, options.stacks, options.duration_s, options.security,
                     options.world, options.processes, options.cacc_law, report=reports)
            for scenario in dict.fromkeys(options.scenarios)
            for fault, faults in options.fault_variants.items()
            for seed in dict.fromkeys(options.seeds)]


def check_runs(options: BatchOptions) -> None:
    """Builds each (scenario, fault variant)'s run as a run would, so that a bad scenario, a fault naming a vehicle
    the scenario lacks or a bad --stacks stops the sweep before anything starts (ScenarioError, one line)."""
    from coopdrive.launch.run import RunOptions, build_specs

    for scenario in dict.fromkeys(options.scenarios):
        for fault, faults in options.fault_variants.items():
            run = RunOptions(scenario=scenario, stacks=options.stacks, security=options.security,
                             world=options.world, extra_faults=faults)
            with tempfile.TemporaryDirectory(prefix="coopdrive-check-") as folder:
                try:
                    build_specs(run, Path(folder))
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
    # Both import this module's data classes.
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
