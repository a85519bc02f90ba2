"""The report page's figures of a replay against a reference (reference_report.py): each error over time inside
the estimate's own 2-sigma bounds, and the NEES against the bound a 2-sigma ellipse sets."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from coopdrive.judging.consistency import TWO_SIGMA_NEES
from coopdrive.judging.plots import plt, save_figure
from coopdrive.judging.reference_errors import ErrorSeries

FIGURE_SIZE_IN = (8.0, 3.2)
# file name -> caption, in the order the page shows them.
FIGURES = {
    "along.png": "Along-track error, and the estimate's own 2-sigma bound along the track",
    "cross.png": "Cross-track error, and the estimate's own 2-sigma bound across the track",
    "heading.png": "Heading error, and the estimate's own 2-sigma bound",
    "nees.png": "NEES of the position: inside the 2-sigma ellipse while at most 4 (86.5 % of the time if consistent)",
}


def _error_with_bound(time_s: np.ndarray, error: np.ndarray, std: np.ndarray | None, ylabel: str, path: Path) -> None:
    figure, axes = plt.subplots(figsize=FIGURE_SIZE_IN)
    if std is not None:
        axes.fill_between(time_s, -2.0 * std, 2.0 * std, color="tab:blue", alpha=0.2, label="±2σ of the estimate")
    axes.plot(time_s, error, color="tab:red", linewidth=1.0, label="error")
    axes.axhline(0.0, color="black", linewidth=0.5)
    axes.set_xlabel("time from the first sample [s]")
    axes.set_ylabel(ylabel)
    axes.legend(loc="upper right")
    save_figure(figure, path)


def _nees(time_s: np.ndarray, nees: np.ndarray, path: Path) -> None:
    figure, axes = plt.subplots(figsize=FIGURE_SIZE_IN)
    axes.semilogy(time_s, np.maximum(nees, 1e-4), color="tab:red", linewidth=1.0, label="NEES")
    axes.axhline(TWO_SIGMA_NEES, color="tab:blue", linestyle="--", label="2-sigma ellipse (NEES = 4)")
    axes.set_xlabel("time from the first sample [s]")
    axes.set_ylabel("NEES")
    axes.legend(loc="upper right")
    save_figure(figure, path)


def write_reference_figures(errors: ErrorSeries, folder: Path) -> list[str]:
    """The figures the series allows (no heading figure without the reference's heading, no NEES without a
    covariance), written into folder; their file names, in FIGURES' order."""
    time_s = errors.time_s - errors.time_s[0]
    _error_with_bound(time_s, errors.along_m, errors.along_std_m, "along-track error [m]", folder / "along.png")
    _error_with_bound(time_s, errors.cross_m, errors.cross_std_m, "cross-track error [m]", folder / "cross.png")
    written = ["along.png", "cross.png"]
    if errors.heading_error_rad is not None:
        std = None if errors.heading_std_rad is None else np.degrees(errors.heading_std_rad)
        _error_with_bound(time_s, np.degrees(errors.heading_error_rad), std, "heading error [deg]",
                          folder / "heading.png")
        written.append("heading.png")
    if errors.nees is not None:
        _nees(time_s, errors.nees, folder / "nees.png")
        written.append("nees.png")
    return written
