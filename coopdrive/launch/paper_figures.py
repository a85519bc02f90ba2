"""Our figures beside the GCDC 2016 papers' (../shared/seeds): every figure a seed paper measured on its own
vehicle that one of our scenarios also measures, with both definitions, over the seeds of a sweep.

    python -m coopdrive.launch.paper_figures out/sweep/summary.json     (the table a sweep's pass table ends with)
    python -m coopdrive.launch.paper_figures A/summary.json B/summary.json     (over sweeps of other seeds)

The papers report one vehicle over one heat; a sweep gives each figure once per seed, so the table shows the mean
over the seeds and the worst seed (the largest error or time)."""

from __future__ import annotations

import argparse
import json
import statistics
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from coopdrive.launch.sweep_faults import NO_FAULTS

if TYPE_CHECKING:
    from coopdrive.launch.batch import BatchSummary, RunOutcome

HEUDIASYC = "Heudiasyc"
# Heudiasyc's errors kept one sign over steady platooning, so their averages are also mean absolute errors.
HEUDIASYC_ONE_SIGN = "their errors kept one sign, so also the mean absolute error"
PLATOON_ERROR = "mean absolute error of every follower against its predecessor over the run"


@dataclass(frozen=True)
class PaperFigure:
    """One measured figure of a paper and the metric of ours that measures the same thing."""

    paper: str
    what: str
    value: float  # their figure, in unit: what ours is held against (tests/control/test_platoon40_run.py)
    theirs: str  # their definition as the paper gives it, "{}" where the figure stands
    where: str  # file and lines in ../shared/seeds
    scenario: str
    metric: str
    unit: str
    ours: str  # how our metric is defined
    spread: tuple[tuple[str, str], ...] = ()  # (label, metric): companions shown beside the mean, in its unit

    def their_figure(self) -> str:
        """Their figure with its definition, as the table shows it."""
        return self.theirs.format(f"{self.value:g} {self.unit}")


PAPER_FIGURES = (
    PaperFigure(HEUDIASYC, "speed error, steady platooning at 40 km/h", 0.71,
                f"{{}}, average (sd 0.03); {HEUDIASYC_ONE_SIGN}", "heudiasyc L323", "platoon40",
                "speed_error_kmh", "km/h", PLATOON_ERROR,
                (("RMS", "speed_error_rms_kmh"), ("p95", "speed_error_p95_kmh"))),
    PaperFigure(HEUDIASYC, "spacing error, steady platooning at 40 km/h", 1.07,
                f"{{}}, average (sd 0.04) against d = r + h v, eq. (4); {HEUDIASYC_ONE_SIGN}", "heudiasyc L323",
                "platoon40", "spacing_error_m", "m", PLATOON_ERROR + ", against d = r + h v (r 6 m, h 1.5 s)",
                (("RMS", "spacing_error_rms_m"), ("p95", "spacing_error_p95_m"))),
    PaperFigure(HEUDIASYC, "lateral error, steady platooning at 40 km/h", 0.29,
                "{}, average (sd 0.18)", "heudiasyc L327", "platoon40", "lateral_error_m", "m",
                "mean absolute distance of every stack from its lane's centre line over the run",
                (("RMS", "lateral_error_rms_m"), ("p95", "lateral_error_p95_m"))),
    PaperFigure(HEUDIASYC, "largest lateral error, steady platooning", 0.6, "{}, the top of [0.05; 0.60] m",
                "heudiasyc L327", "platoon40", "lateral_error_max_m", "m",
                "largest distance of any stack from its lane's centre line"),
    PaperFigure(HEUDIASYC, "lane change of a merge", 10.0, "a bit less than {}, at 40 km/h", "heudiasyc L336",
                "merge", "lane_change_time_s", "s",
                "slowest merger's lane change, leaving the closed lane's centre to settling in the open one "
                "(60-80 km/h)"),
)

# Measured figures of the papers with no like metric in a sweep, and why.
UNMATCHED = (
    "Heudiasyc's CAM reception (median above 20 Hz of 25, L348): ours is a report figure "
    "(`v2x_reception_ratio_min`), not in a sweep without reports.",
    "Heudiasyc's sub-metre GNSS more than 80 % of the time (L293) is the receiver's own accuracy estimate, not an "
    "error against ground truth; ours are the localisation report's errors against the truth.",
    "Drivertive's speed controller, under 0.7 km/h steady-state error at 60 km/h (L122), is a low-level loop "
    "against a speed reference, and their 'around 30 m' from the organiser's vehicle at the intersection (L328) a "
    "reading of V2X logs; no metric of ours measures either.",
    "Chalmers report no measured performance of their truck: their one figure is a discrepancy of more than 4 m "
    "between its two GPS receivers (L618).",
)


def _value(outcome: RunOutcome, key: str) -> float | None:
    value = outcome.metrics.get(key)
    return None if value is None else float(value)


def _cell(values: list[float], unit: str) -> str:
    return f"{statistics.fmean(values):.3g} {unit}"


def figure_row(figure: PaperFigure, outcomes: list[RunOutcome]) -> str | None:
    """The table's row of one figure over the runs of its scenario that report it; None where none does."""
    reporting = [(o, value) for o in outcomes if (value := _value(o, figure.metric)) is not None]
    if not reporting:
        return None
    worst, worst_value = max(reporting, key=lambda pair: pair[1])
    mean = _cell([value for _, value in reporting], figure.unit)
    spreads = []
    for label, key in figure.spread:
        values = [v for v in (_value(o, key) for o, _ in reporting) if v is not None]
        if values:
            spreads.append(f"{label} {_cell(values, figure.unit)}")
    if spreads:
        mean += " (" + ", ".join(spreads) + ")"
    worst_cell = f"{worst_value:.3g} {figure.unit} (seed {worst.seed})"
    return (f"| {figure.paper}: {figure.what} | {figure.their_figure()} ({figure.where}) | {figure.scenario} "
            f"`{figure.metric}`: {figure.ours} | {len(reporting)} | {mean} | {worst_cell} |")


def paper_table_markdown(summary: BatchSummary) -> str:
    """The papers' figures beside ours, over each scenario's runs without faults; "" where the sweep ran none of
    the scenarios they concern."""
    by_case = summary.by_case()
    rows = [row for figure in PAPER_FIGURES
            if (row := figure_row(figure, by_case.get((figure.scenario, NO_FAULTS), []))) is not None]
    if not rows:
        return ""
    header = ["| the paper's figure | theirs (their definition) | ours (our definition) | seeds | mean of the seeds "
              "| worst seed |", "|---|---|---|---|---|---|"]
    return "\n".join(header + rows + [""] + [f"- {line}" for line in UNMATCHED]) + "\n"


def load_summary(*paths: Path) -> BatchSummary:
    """Sweeps' summary.json files (sweep_output.write_summary) back as one BatchSummary of all their runs: a sweep
    split over sessions or clusters by seeds gives one table."""
    from coopdrive.launch.batch import BatchSummary, RunOutcome

    return BatchSummary([RunOutcome(**row) for path in paths for row in json.loads(Path(path).read_text())])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("summary", type=Path, nargs="+", help="a sweep's summary.json, or several")
    print(paper_table_markdown(load_summary(*parser.parse_args(argv).summary)), end="")


if __name__ == "__main__":
    main()
