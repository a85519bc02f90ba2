"""Batch runs: every (scenario, seed) in parallel worker processes, a progress bar, and a summary table.

`coopdrive run all --seeds 1-20` and `coopdrive run merge --seeds 1-5` come here. Each run is an ordinary
lockstep run in its own worker (so the same seed gives the same metrics as a single run); with --out each
writes <out>/<scenario>/seed-<n>/metrics.json and the batch writes summary.json, summary.csv and pass_table.md.
"""

from __future__ import annotations

import csv
import json
import multiprocessing
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from coopdrive.launch.pass_table import pass_table_markdown
from coopdrive.services.sim.scenario_config import SCENARIO_PACKAGE

# Metrics averaged in the summary table, when the runs report them.
TABLE_METRICS = ("collisions", "min_gap_m", "spacing_error_m", "string_gain", "rms_jerk_mps3")


@dataclass
class BatchOptions:
    scenarios: list[str]
    seeds: list[int]
    stacks: int | None = None
    workers: int = 2
    out_dir: Path | None = None
    duration_s: float | None = None
    # V2X security of every stack in every run (a SecurityMode value), as `coopdrive run --security`.
    security: str | None = None
    # The world every run is in, as `coopdrive run --world`.
    world: str = "real"


@dataclass
class RunOutcome:
    scenario: str
    seed: int
    success: bool
    failure_reason: str
    wall_time_s: float = 0.0
    metrics: dict[str, float] = field(default_factory=dict)


@dataclass
class BatchSummary:
    outcomes: list[RunOutcome]

    @property
    def all_passed(self) -> bool:
        return bool(self.outcomes) and all(o.success for o in self.outcomes)

    def by_scenario(self) -> dict[str, list[RunOutcome]]:
        grouped: dict[str, list[RunOutcome]] = {}
        for outcome in sorted(self.outcomes, key=lambda o: (o.scenario, o.seed)):
            grouped.setdefault(outcome.scenario, []).append(outcome)
        return grouped


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


def run_one(scenario: str, seed: int, stacks: int | None, duration_s: float | None,
            out_dir: str | None, security: str | None = None, world: str = "real") -> RunOutcome:
    """One run in a worker process (module level, so the spawn context can import it)."""
    from coopdrive.launch.run import RunOptions, run_scenario

    try:
        result = run_scenario(RunOptions(scenario=scenario, seed=seed, stacks=stacks, duration_s=duration_s,
                                         security=security, world=world))
        outcome = RunOutcome(scenario, seed, result.success, result.failure_reason, result.wall_time_s,
                             dict(result.metrics))
    except Exception as error:  # a run that cannot even start is a failed run, not a failed batch
        outcome = RunOutcome(scenario, seed, False, f"{type(error).__name__}: {error}")
    if out_dir is not None:
        folder = Path(out_dir) / scenario / f"seed-{seed}"
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "metrics.json").write_text(json.dumps(vars(outcome), indent=2))
    return outcome


def run_batch(options: BatchOptions, console: Console | None = None) -> BatchSummary:
    console = console or Console()
    jobs = list(dict.fromkeys((scenario, seed) for scenario in options.scenarios for seed in options.seeds))
    outcomes: list[RunOutcome] = []
    out = str(options.out_dir) if options.out_dir is not None else None
    context = multiprocessing.get_context("spawn")
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=console) as progress, \
            ProcessPoolExecutor(max_workers=max(1, options.workers), mp_context=context) as pool:
        task = progress.add_task("runs", total=len(jobs))
        pending: dict[Future, tuple[str, int]] = {
            pool.submit(run_one, scenario, seed, options.stacks, options.duration_s, out, options.security,
                        options.world):
                (scenario, seed)
            for scenario, seed in jobs}
        try:
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    scenario, seed = pending.pop(future)
                    try:
                        outcomes.append(future.result())
                    except Exception as error:  # the worker itself died
                        outcomes.append(RunOutcome(scenario, seed, False, f"worker failed: {error}"))
                    progress.advance(task)
        except KeyboardInterrupt:
            for future in pending:
                future.cancel()
            console.print(f"[yellow]interrupted: {len(pending)} run(s) not finished[/]")
    summary = BatchSummary(outcomes)
    console.print(summary_table(summary))
    if options.out_dir is not None:
        write_summary(summary, options.out_dir)
    return summary


def summary_table(summary: BatchSummary) -> Table:
    table = Table(title="coopdrive batch")
    for column in ("scenario", "runs", "pass rate", *TABLE_METRICS, "first failure"):
        table.add_column(column, justify="left" if column in ("scenario", "first failure") else "right")
    for scenario, outcomes in summary.by_scenario().items():
        passed = sum(o.success for o in outcomes)
        means = []
        for key in TABLE_METRICS:
            values = [o.metrics[key] for o in outcomes if key in o.metrics]
            means.append(f"{sum(values) / len(values):.3f}" if values else "-")
        failure = next((f"seed {o.seed}: {o.failure_reason}" for o in outcomes if not o.success), "")
        table.add_row(scenario, str(len(outcomes)), f"{passed / len(outcomes):.0%}", *means, failure)
    return table


def write_summary(summary: BatchSummary, out_dir: Path) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = [vars(o) for o in sorted(summary.outcomes, key=lambda o: (o.scenario, o.seed))]
    (out_dir / "summary.json").write_text(json.dumps(rows, indent=2))
    keys = sorted({key for o in summary.outcomes for key in o.metrics})
    with open(out_dir / "summary.csv", "w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["scenario", "seed", "success", "failure_reason", "wall_time_s", *keys])
        for o in sorted(summary.outcomes, key=lambda o: (o.scenario, o.seed)):
            writer.writerow([o.scenario, o.seed, o.success, o.failure_reason, round(o.wall_time_s, 3),
                             *(o.metrics.get(key, "") for key in keys)])
    (out_dir / "pass_table.md").write_text(pass_table_markdown(summary))
