"""Batch runs (sweeps): every (scenario, fault variant, seed) on a Dask cluster, a live progress bar and
summary table, and the summary files.

`coopdrive run all --seeds 1-20` and `coopdrive run merge --seeds 1-5 --faults FILE --cluster ADDRESS` come here.
Each run is an ordinary lockstep run on a worker (so the same seed gives the same metrics as a single run); with
--out each run's folder <out>/<scenario>/<fault>/seed-<n>/ holds metrics.json and the run's report (report/), and
the sweep writes summary.json, summary.csv and pass_table.md. This module holds what a sweep is and what it gives
(every sweep_*.py module reads it); sweep.py runs one, sweep_cluster.py is the Dask side.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run_spec import RunSpec
from coopdrive.launch.sweep_faults import NO_FAULTS
from coopdrive.services.sim.scenario_config import SCENARIO_PACKAGE

@dataclass
class BatchOptions:
    scenarios: list[str]
    seeds: list[int]
    # What every run is, but its scenario, seed and faults (the sweep's dimensions). One process per run by default:
    # the sweep's runs already fill the cores, and a run in one process spends 20-30 % less CPU than one spread
    # over a process per vehicle (docs/performance.md).
    run: RunSpec = RunSpec(processes=ProcessLayout.ONE)
    workers: int = 2
    out_dir: Path | None = None
    # With out_dir: each run's report (plots, index.html and its recording) beside its metrics.json. False: the
    # metrics and summaries only, for a sweep that is judged by its pass table alone (CI's).
    reports: bool = True
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
