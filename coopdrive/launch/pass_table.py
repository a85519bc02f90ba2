"""The pass table of a sweep: which (scenario, seed) passed, why the others failed, and each scenario's error
figures averaged over its runs (each figure as the runs define it: mean absolute error, see the README)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

if TYPE_CHECKING:
    from coopdrive.launch.batch import BatchSummary, RunOutcome

FIGURES = ("speed_error_kmh", "spacing_error_m", "lateral_error_m", "min_gap_m", "collisions")
PASSED, FAILED = "pass", "FAIL"


def mean_cell(outcomes: Iterable[RunOutcome], key: str) -> str:
    """One figure averaged over the runs that report it, as a table shows it ("-": none does)."""
    values = [o.metrics[key] for o in outcomes if o.metrics.get(key) is not None]
    return f"{sum(values) / len(values):.3f}" if values else "-"


def pass_table_markdown(summary: BatchSummary) -> str:
    grouped = summary.by_scenario()
    seeds = sorted({o.seed for o in summary.outcomes})
    lines = ["| scenario | passed | " + " | ".join(f"seed {seed}" for seed in seeds) + " |",
             "|---|---|" + "---|" * len(seeds)]
    for scenario, outcomes in grouped.items():
        by_seed = {o.seed: o for o in outcomes}
        cells = [(PASSED if by_seed[seed].success else FAILED) if seed in by_seed else "" for seed in seeds]
        passed = sum(o.success for o in outcomes)
        lines.append(f"| {scenario} | {passed}/{len(outcomes)} | " + " | ".join(cells) + " |")
    lines += ["", "| scenario | " + " | ".join(FIGURES) + " |", "|---|" + "---|" * len(FIGURES)]
    for scenario, outcomes in grouped.items():
        lines.append(f"| {scenario} | " + " | ".join(mean_cell(outcomes, key) for key in FIGURES) + " |")
    failures = [o for outcomes in grouped.values() for o in outcomes if not o.success]
    if failures:
        lines += ["", "Failures:", ""] + [f"- {o.scenario} seed {o.seed}: {o.failure_reason}" for o in failures]
    return "\n".join(lines) + "\n"
