"""The report's figures from a TruthSeries: speeds, gaps, accelerations, bird's-eye map, space-time diagram."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from coopdrive.services.sim import metrics as judge_metrics  # noqa: E402
from coopdrive.services.sim.truth_series import TruthSeries  # noqa: E402

FIGURE_SIZE_IN = (8.0, 4.0)
DPI = 100

# file name -> caption, in the order the report shows them.
FIGURES = {
    "speeds.png": "Speed of every vehicle over time",
    "gaps.png": "Bumper gap of each follower to its predecessor, and the desired d = r + h v",
    "accelerations.png": "Acceleration of every vehicle over time",
    "trajectories.png": "Bird's-eye view of the trajectories (local ENU)",
    "space_time.png": "Space-time diagram: position along the lane over time",
}


def save_figure(figure, path: Path) -> None:
    figure.tight_layout()
    figure.savefig(path, dpi=DPI)
    plt.close(figure)


def _per_vehicle(series: TruthSeries, name: str, ylabel: str, path: Path) -> None:
    figure, axes = plt.subplots(figsize=FIGURE_SIZE_IN)
    for vehicle_id in series.vehicle_ids:
        axes.plot(series.time_s, series.get(vehicle_id, name), label=vehicle_id)
    axes.set_xlabel("time [s]")
    axes.set_ylabel(ylabel)
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best")
    save_figure(figure, path)


def _gaps(series: TruthSeries, path: Path, standstill_m: float, headway_s: float) -> None:
    pairs: dict[tuple[str, str], list[tuple[float, float, float]]] = {}
    for time_s, vehicles in series.frames:
        for leader, follower in judge_metrics.following_pairs(vehicles):
            desired = standstill_m + headway_s * follower.speed_mps  # (eq. 4) Heudiasyc spacing
            pairs.setdefault((leader.vehicle_id, follower.vehicle_id), []).append(
                (time_s, judge_metrics.bumper_gap_m(leader, follower), desired))
    figure, axes = plt.subplots(figsize=FIGURE_SIZE_IN)
    for (leader, follower), rows in sorted(pairs.items()):
        values = np.array(rows)
        line, = axes.plot(values[:, 0], values[:, 1], label=f"{follower} behind {leader}")
        axes.plot(values[:, 0], values[:, 2], linestyle="--", color=line.get_color(), alpha=0.6,
                  label=f"{follower} desired")
    axes.set_xlabel("time [s]")
    axes.set_ylabel("gap [m]")
    axes.grid(True, alpha=0.3)
    if pairs:
        axes.legend(loc="best")
    save_figure(figure, path)


def _trajectories(series: TruthSeries, path: Path) -> None:
    figure, axes = plt.subplots(figsize=FIGURE_SIZE_IN)
    for vehicle_id in series.vehicle_ids:
        x, y = series.get(vehicle_id, "x_m"), series.get(vehicle_id, "y_m")
        line, = axes.plot(x, y, label=vehicle_id)
        valid = np.flatnonzero(np.isfinite(x) & np.isfinite(y))
        if valid.size:
            axes.plot(x[valid[0]], y[valid[0]], "o", color=line.get_color())
            axes.plot(x[valid[-1]], y[valid[-1]], "s", color=line.get_color())
    axes.set_xlabel("east [m]  (o start, square end)")
    axes.set_ylabel("north [m]")
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best")
    save_figure(figure, path)


def write_figures(series: TruthSeries, folder: Path, standstill_m: float = judge_metrics.DEFAULT_STANDSTILL_M,
                  headway_s: float = judge_metrics.DEFAULT_HEADWAY_S) -> list[str]:
    """Writes every figure of FIGURES into folder; returns their file names."""
    folder.mkdir(parents=True, exist_ok=True)
    _per_vehicle(series, "speed_mps", "speed [m/s]", folder / "speeds.png")
    _gaps(series, folder / "gaps.png", standstill_m, headway_s)
    _per_vehicle(series, "accel_mps2", "acceleration [m/s²]", folder / "accelerations.png")
    _trajectories(series, folder / "trajectories.png")
    _per_vehicle(series, "station_m", "station along the lane [m]", folder / "space_time.png")
    return list(FIGURES)
