"""What a sweep shows and writes: the summary table, each run's folder, summary.json/.csv and the pass table."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from rich.console import Console, RenderableType
from rich.markup import escape
from rich.measure import Measurement
from rich.table import Table

from coopdrive.launch.batch import BatchSummary, RunOutcome
from coopdrive.launch.pass_table import mean_cell, pass_table_markdown

# Metrics averaged in the summary table, when the runs report them.
TABLE_METRICS = ("collisions", "min_gap_m", "spacing_error_m", "string_gain", "rms_jerk_mps3")
REPORT_FOLDER = "report"
LEFT_ALIGNED = ("scenario", "fault", "first failure")
# Columns a table may take when printed to a file.
UNLIMITED_WIDTH = 10_000


def summary_table(summary: BatchSummary) -> Table:
    table = Table(title="coopdrive batch")
    for column in ("scenario", "fault", "runs", "pass rate", "retried", *TABLE_METRICS, "first failure"):
        table.add_column(column, justify="left" if column in LEFT_ALIGNED else "right")
    for (scenario, fault), outcomes in summary.by_case().items():
        passed = sum(o.success for o in outcomes)
        means = [mean_cell(outcomes, key) for key in TABLE_METRICS]
        failure = next((f"seed {o.seed}: {o.failure_reason}" for o in outcomes if not o.success), "")
        table.add_row(escape(scenario), escape(fault), str(len(outcomes)), f"{passed / len(outcomes):.0%}",
                      str(sum(o.retried for o in outcomes)), *means, escape(failure))
    return table


def run_line(outcome: RunOutcome, done: int, total: int) -> str:
    """A finished run in one line, where the sweep's output is not a terminal (a log, CI): a live table shows
    nothing there until the sweep ends."""
    verdict = "pass" if outcome.success else f"[red]FAIL[/] {escape(outcome.failure_reason)}"
    retried = ", retried" if outcome.retried else ""
    return f"{done}/{total} {escape(outcome.label)}: {verdict} ({outcome.wall_time_s:.0f} s{retried})"


def print_whole(console: Console, renderable: RenderableType) -> None:
    """To output that is not a terminal, as wide as it needs: a console's 80 columns there would cut every cell
    short."""
    terminal_width = console.width
    console.width = max(terminal_width, Measurement.get(console, console.options.update(max_width=UNLIMITED_WIDTH),
                                                        renderable).maximum)
    try:
        console.print(renderable)
    finally:
        console.width = terminal_width


def retried_lines(summary: BatchSummary) -> list[str]:
    """One console line per run that a worker's death made run again."""
    return [f"[yellow]retried[/] {escape(o.label)} after its worker died: {escape(', '.join(o.lost_workers))}"
            for o in summary.in_order() if o.retried]


def run_folder(out_dir: Path, outcome: RunOutcome) -> Path:
    # A scenario given as a file is named by its stem: a path would put the folder outside out_dir.
    name = Path(outcome.scenario).stem if outcome.scenario.endswith((".yaml", ".yml")) else outcome.scenario
    return Path(out_dir) / name / outcome.fault / f"seed-{outcome.seed}"


def write_run(out_dir: Path, outcome: RunOutcome, report_files: dict[str, bytes]) -> None:
    """<out>/<scenario>/<fault>/seed-<n>/: metrics.json (the outcome) and the run's report in report/."""
    folder = run_folder(out_dir, outcome)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "metrics.json").write_text(json.dumps(vars(outcome), indent=2))
    for relative, content in report_files.items():
        path = folder / REPORT_FOLDER / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)


def write_summary(summary: BatchSummary, out_dir: Path) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = summary.in_order()
    (out_dir / "summary.json").write_text(json.dumps([vars(o) for o in rows], indent=2))
    keys = sorted({key for o in rows for key in o.metrics})
    with open(out_dir / "summary.csv", "w", newline="") as stream:
        writer = csv.writer(stream)
        writer.writerow(["scenario", "fault", "seed", "success", "failure_reason", "wall_time_s", "retried", *keys])
        for o in rows:
            writer.writerow([o.scenario, o.fault, o.seed, o.success, o.failure_reason, round(o.wall_time_s, 3),
                             o.retried, *(o.metrics.get(key, "") for key in keys)])
    (out_dir / "pass_table.md").write_text(pass_table_markdown(summary))
