"""A series' errors against a reference, sample by sample, with the estimate's own 2-sigma bounds: what the
figures of reference_score.py summarise and what the report page (reference_report.py) draws over time.

Along- and across-track are the reference's heading's directions; an estimate's bound along a direction u is
2 sqrt(u' P u) of its position covariance P there, its heading's 2 sqrt(P_hh).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coopdrive.judging.reference_track import ReferenceTrack, wrap_rad


@dataclass(frozen=True)
class ErrorSeries:
    time_s: np.ndarray  # the series' own times (the reference taken offset_s later)
    along_m: np.ndarray
    cross_m: np.ndarray
    heading_error_rad: np.ndarray | None = None
    speed_error_mps: np.ndarray | None = None
    # With the estimate's covariance: its std along and across the track and of its heading, and the NEES.
    along_std_m: np.ndarray | None = None
    cross_std_m: np.ndarray | None = None
    heading_std_rad: np.ndarray | None = None
    nees: np.ndarray | None = None

    @property
    def horizontal_m(self) -> np.ndarray:
        return np.hypot(self.along_m, self.cross_m)


def error_series(points: np.ndarray, covariance: np.ndarray | None, series, reference: ReferenceTrack,
                 keep: np.ndarray, offset_s: float) -> ErrorSeries:
    """points: (n, 2) east-north of the compared point, covariance (n, 2, 2) or None (reference_score.py); the
    samples kept are those whose shifted time lies within the reference."""
    at = reference.at(series.time_s[keep] + offset_s)
    error = points[keep] - np.column_stack((at["east_m"], at["north_m"]))
    c, s = np.cos(at["heading_rad"]), np.sin(at["heading_rad"])
    along_unit, cross_unit = np.column_stack((c, s)), np.column_stack((-s, c))
    heading_error = speed_error = None
    if series.heading_rad is not None and reference.has_heading:
        heading_error = wrap_rad(series.heading_rad[keep] - at["heading_rad"])
    if series.speed_mps is not None and "speed_mps" in at:
        speed_error = series.speed_mps[keep] - at["speed_mps"]
    bounds = {}
    if covariance is not None:
        kept = covariance[keep]
        bounds = {"along_std_m": np.sqrt(np.einsum("ni,nij,nj->n", along_unit, kept, along_unit)),
                  "cross_std_m": np.sqrt(np.einsum("ni,nij,nj->n", cross_unit, kept, cross_unit)),
                  "nees": np.einsum("ni,nij,nj->n", error, np.linalg.inv(kept), error)}
        if series.covariance is not None:
            bounds["heading_std_rad"] = np.sqrt(series.covariance[keep][:, 2, 2])
    return ErrorSeries(series.time_s[keep], np.sum(error * along_unit, axis=1), np.sum(error * cross_unit, axis=1),
                       heading_error, speed_error, **bounds)
