"""The pass table of a sweep: which (scenario, fault variant, seed) passed, why the others failed, which a worker's
death made run again, and each case's error figures averaged over its runs (each figure as the runs define it:
mean absolute error, see the README)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

from coopdrive.launch.lockstep_give_ups import GIVE_UP_MEANING
from coopdrive.launch.paper_figures import paper_table_markdown
from coopdrive.runtime.barrier import MESSAGES_GIVEN_UP_COUNTER

if TYPE_CHECKING:
    from coopdrive.launch.batch import BatchSummary, RunOutcome

FIGURES = ("speed_error_kmh", "spacing_error_m", "lateral_error_m", "min_gap_m", "collisions", "phantom_brakes")
PASSED, FAILED = "pass", "FAIL"


def mean_cell(outcomes: Iterable[RunOutcome], key: str) -> str:
    """One figure averaged over the runs that report it, as a table shows it ("-": none does)."""
    values = [o.metrics[key] for o in outcomes if o.metrics.get(key) is not None]
    return f"{sum(values) / len(values):.3f}" if values else "-"


def pass_table_markdown(summary: BatchSummary) -> str:
    grouped = summary.by_case()
    seeds = sorted({o.seed for o in summary.outcomes})
    lines = ["| " + " | ".join(["scenario", "fault", "passed"] + [f"seed {seed}" for seed in seeds]) + " |",
             "|---|---|---|" + "---|" * len(seeds)]
    for (scenario, fault), outcomes in grouped.items():
        by_seed = {o.seed: o for o in outcomes}
        cells = [(PASSED if by_seed[seed].success else FAILED) if seed in by_seed else "" for seed in seeds]
        passed = sum(o.success for o in outcomes)
        lines.append(f"| {scenario} | {fault} | {passed}/{len(outcomes)} | " + " | ".join(cells) + " |")
    lines += ["", "| scenario | fault | " + " | ".join(FIGURES) + " |", "|---|---|" + "---|" * len(FIGURES)]
    for (scenario, fault), outcomes in grouped.items():
        lines.append(f"| {scenario} | {fault} | " + " | ".join(mean_cell(outcomes, key) for key in FIGURES) + " |")
    ordered = summary.in_order()
    failures = [o for o in ordered if not o.success]
    if failures:
        lines += ["", "Failures:", ""] + [f"- {o.label}: {o.failure_reason}" for o in failures]
    unsteady = [o for o in ordered if o.metrics.get(MESSAGES_GIVEN_UP_COUNTER, 0) > 0]
    if unsteady:
        lines += ["", f"Not deterministic ({GIVE_UP_MEANING}: an overloaded host; run it again alone):", ""] + [
            f"- {o.label}: {int(o.metrics[MESSAGES_GIVEN_UP_COUNTER])} times" for o in unsteady]
    phantom = [o for o in ordered if o.metrics.get("phantom_brakes", 0) > 0]
    if phantom:
        lines += ["", "Phantom brakes (hard brakes nothing in the lane called for; not part of the verdict):", ""]
        lines += [f"- {o.label}: {int(o.metrics['phantom_brakes'])}" for o in phantom]
    retried = [o for o in ordered if o.retried]
    if retried:
        lines += ["", "Retried (a worker died under them):", ""] + [
            f"- {o.label}: lost {', '.join(o.lost_workers)}" for o in retried]
    if summary.unfinished:
        lines += ["", f"Not finished (the sweep's {summary.end.value}):", ""] + [
            f"- {label}" for label in summary.unfinished]
    papers = paper_table_markdown(summary)
    if papers:
        lines += ["", "Beside the GCDC 2016 papers (coopdrive/launch/paper_figures.py):", "", papers.rstrip("\n")]
    return "\n".join(lines) + "\n"
