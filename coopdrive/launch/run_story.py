"""What `coopdrive run` tells a person at the end of a run: a verdict line, a few sentences on what happened, five
key figures with their units, and where to go next. The whole table of metrics is behind --json and --report."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.table import Table

from coopdrive.launch.summary import print_fault_reactions, summary_dict, warn_if_not_deterministic
from coopdrive.v1 import sim_pb2

# How many figures the story shows.
KEY_FIGURE_COUNT = 5


@dataclass(frozen=True)
class KeyFigure:
    metric: str
    label: str
    unit: str


# In order of preference: the first KEY_FIGURE_COUNT the run has are shown (a scenario judges what it judges).
KEY_FIGURES = (
    KeyFigure("min_gap_m", "closest gap", "m"),
    KeyFigure("min_time_gap_s", "closest time gap", "s"),
    # Mean absolute errors: a signed mean would let errors of both signs cancel (the story gives the RMS too).
    KeyFigure("spacing_error_m", "spacing error, mean absolute", "m"),
    KeyFigure("speed_error_kmh", "speed error, mean absolute", "km/h"),
    KeyFigure("max_abs_accel_mps2", "largest acceleration", "m/s²"),
    KeyFigure("string_gain", "string gain (< 1 damps)", ""),
    KeyFigure("lateral_error_rms_m", "lateral error, RMS", "m"),
    KeyFigure("position_rmse_m", "position error, RMS", "m"),
    KeyFigure("rms_jerk_mps3", "jerk, RMS", "m/s³"),
)


def key_figures(summary: dict) -> list[tuple[KeyFigure, float]]:
    present = [(figure, summary[figure.metric]) for figure in KEY_FIGURES if figure.metric in summary]
    return present[:KEY_FIGURE_COUNT]


def verdict_line(summary: dict) -> str:
    run = f"{summary['scenario']} (seed {summary['seed']})"
    if summary["success"]:
        return f"PASS  {run}"
    return f"FAIL  {run}: {summary['failure_reason']}"


def sentences(summary: dict, description: str) -> list[str]:
    """Two or three sentences: what the scenario does, how closely the stack kept its spacing, how safe it was."""
    told = [description] if description else []
    if {"spacing_error_rms_m", "spacing_error_max_m", "min_gap_m"} <= summary.keys():
        told.append(f"Every stack stayed within {summary['spacing_error_max_m']:.1f} m of its spacing policy "
                    f"({summary['spacing_error_rms_m']:.1f} m RMS) and never came closer than "
                    f"{summary['min_gap_m']:.1f} m to the vehicle ahead.")
    simulated, wall = summary["sim_time_s"], summary["wall_time_s"]
    told.append(f"{summary['collisions']} collisions and {summary.get('hard_brakes', 0)} hard brakes in "
                f"{simulated:.0f} s simulated ({wall:.0f} s of stepping, {summary['realtime_factor']:.1f}x real time).")
    return told


def next_steps(scenario: str, recording: Path | None, report: Path | None) -> list[str]:
    steps = []
    if recording is not None:
        steps += [f"recording: {recording}  (Foxglove: Open local file, layout docs/foxglove-layout.json)",
                  f"replay a service:  coopdrive replay {recording} --service control"]
    if report is None:
        steps.append(f"every metric:  coopdrive run {scenario} --json, or --report out/{scenario}-report for plots")
    else:
        steps.append(f"report: {report / 'index.html'}")
    return steps


def tell(result: sim_pb2.RunResult, description: str = "", recording: Path | None = None,
         report: Path | None = None) -> None:
    summary = summary_dict(result)
    console = Console(highlight=False)  # rich's repr highlighter compiles its regexes on first use: 0.3 s
    colour = "green" if result.success else "red"
    console.print(f"[bold {colour}]{verdict_line(summary)}[/]")
    print_fault_reactions(console, result)
    for sentence in sentences(summary, description):
        console.print(sentence)
    table = Table(show_header=False, box=None, padding=(0, 2))
    for figure, value in key_figures(summary):
        table.add_row(figure.label, f"{value:.2f} {figure.unit}".rstrip())
    console.print(table)
    warn_if_not_deterministic(console, summary)
    console.print("next:")
    for step in next_steps(summary["scenario"], recording, report):
        console.print(f"  {step}", soft_wrap=True)  # a command stays whole, to be copied
