"""How far a replayed estimate (and the fixes it fused) lies from a reference trajectory (reference_track.py).

Figures, as the literature defines them (horizontal = the east-north plane; errors are estimate minus reference):
- rms_m, mean_abs_m, p95_m, max_m: of the horizontal error's length;
- along_rms_m, cross_rms_m: its parts along and across the reference's heading;
- heading_rms_deg, speed_rms_mps: when the reference has them;
- claimed_drms_m: what the estimate claims of its own horizontal error, the RMS over the samples of its covariance's
  DRMS, sqrt(sigma_e^2 + sigma_n^2): beside rms_m, how honest it is;
- two_sigma_share: share of estimates whose own 2-sigma ellipse holds the reference (normalised estimation error
  squared, NEES = e' P^-1 e, at most 2^2 = 4); for a consistent 2-D estimate it is 1 - exp(-2) = 86.5 % (95.45 % is
  the one-dimensional figure); nees_mean: its mean, 2 for a consistent 2-D estimate (Bar-Shalom, Li and Kirubarajan,
  Estimation with Applications to Tracking and Navigation, 5.4.2), and nees_lower_95 / nees_upper_95 its chi-square
  95 % bounds for the samples at least a second apart (coopdrive/judging/consistency.py).

Two sources need not share a clock to the millisecond (a receiver's output latency, a logger's clock): the figures
are given at the best-fit time offset, the one of least horizontal RMS within +-max_offset_s (the reference taken
offset_s later than each estimate's time), and at the stamped times (offset 0).

The estimate is compared at a point of the vehicle: the rear axle it reports, moved by a lever arm (by default the
recorded geolocation config's GNSS antenna, where the fixes are), its covariance carried there through the heading's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coopdrive.judging.consistency import TWO_SIGMA_NEES, decimated, mean_nees_bounds
from coopdrive.judging.reference_errors import ErrorSeries, error_series
from coopdrive.judging.reference_track import ReferenceTrack
from coopdrive.services.geolocation.frames import LeverArm

DEFAULT_MAX_OFFSET_S = 0.5
OFFSET_STEP_S = 0.001
P95 = 95.0


@dataclass
class TrackSeries:
    """Positions to judge, time-ordered: an estimate's with its covariance, or a receiver's fixes."""

    name: str
    time_s: np.ndarray
    lat_deg: np.ndarray
    lon_deg: np.ndarray
    heading_rad: np.ndarray | None = None  # ENU, counter-clockwise from east
    speed_mps: np.ndarray | None = None
    covariance: np.ndarray | None = None  # (n, 3, 3): east, north, heading
    lever_arm: LeverArm = LeverArm()


@dataclass
class ReferenceScore:
    name: str
    samples: int
    offset_s: float
    best_fit: dict[str, float]
    stamped: dict[str, float]
    errors: ErrorSeries | None = None  # sample by sample at the best-fit offset, for the report page

    def as_dict(self) -> dict:
        return {"name": self.name, "samples": self.samples, "best_fit_offset_s": self.offset_s,
                "at_best_fit_offset": self.best_fit, "at_stamped_times": self.stamped}


def _compared_points(series: TrackSeries, reference: ReferenceTrack) -> tuple[np.ndarray, np.ndarray | None]:
    """(n, 2) east-north of the compared point on the reference's plane, and its (n, 2, 2) covariance."""
    enu = np.array([reference.plane.to_enu(float(lat), float(lon))[:2]
                    for lat, lon in zip(series.lat_deg, series.lon_deg)])
    arm = series.lever_arm
    if series.heading_rad is not None and (arm.x_m or arm.y_m):
        c, s = np.cos(series.heading_rad), np.sin(series.heading_rad)
        enu = enu + np.column_stack((c * arm.x_m - s * arm.y_m, s * arm.x_m + c * arm.y_m))
    if series.covariance is None:
        return enu, None
    # The point's covariance: J P J' with J = [I, d(point)/d(heading)].
    jacobian = np.zeros((len(enu), 2, 3))
    jacobian[:, 0, 0] = jacobian[:, 1, 1] = 1.0
    if series.heading_rad is not None:
        c, s = np.cos(series.heading_rad), np.sin(series.heading_rad)
        jacobian[:, 0, 2] = -s * arm.x_m - c * arm.y_m
        jacobian[:, 1, 2] = c * arm.x_m - s * arm.y_m
    return enu, jacobian @ series.covariance @ np.transpose(jacobian, (0, 2, 1))


def _inside(series: TrackSeries, reference: ReferenceTrack, offset_s: float, margin_s: float = 0.0) -> np.ndarray:
    first_s, last_s = reference.span_s()
    shifted = series.time_s + offset_s
    return (shifted >= first_s + margin_s) & (shifted <= last_s - margin_s)


def _horizontal_rms(points: np.ndarray, series: TrackSeries, reference: ReferenceTrack, offset_s: float,
                    keep: np.ndarray) -> float:
    at = reference.at(series.time_s[keep] + offset_s)
    error = points[keep] - np.column_stack((at["east_m"], at["north_m"]))
    return float(np.sqrt(np.mean(np.sum(error**2, axis=1))))


def best_fit_offset_s(points: np.ndarray, series: TrackSeries, reference: ReferenceTrack,
                      max_offset_s: float) -> float:
    """The offset of least horizontal RMS on a 1 ms grid, over the samples every offset of the grid can compare."""
    keep = _inside(series, reference, 0.0, margin_s=max_offset_s)
    if not keep.any():
        return 0.0
    offsets_s = np.arange(-max_offset_s, max_offset_s + OFFSET_STEP_S / 2.0, OFFSET_STEP_S)
    rms_m = [_horizontal_rms(points, series, reference, offset_s, keep) for offset_s in offsets_s]
    return float(offsets_s[int(np.argmin(rms_m))])


def _figures(errors: ErrorSeries) -> dict[str, float]:
    if not len(errors.time_s):
        return {"samples": 0}
    length = errors.horizontal_m
    figures = {"samples": len(errors.time_s), "rms_m": float(np.sqrt(np.mean(length**2))),
               "mean_abs_m": float(np.mean(length)), "p95_m": float(np.percentile(length, P95)),
               "max_m": float(np.max(length)), "along_rms_m": float(np.sqrt(np.mean(errors.along_m**2))),
               "cross_rms_m": float(np.sqrt(np.mean(errors.cross_m**2)))}
    if errors.heading_error_rad is not None:
        figures["heading_rms_deg"] = float(np.degrees(np.sqrt(np.mean(errors.heading_error_rad**2))))
    if errors.speed_error_mps is not None:
        figures["speed_rms_mps"] = float(np.sqrt(np.mean(errors.speed_error_mps**2)))
    if errors.along_std_m is not None:
        figures["claimed_drms_m"] = float(np.sqrt(np.mean(errors.along_std_m**2 + errors.cross_std_m**2)))
    if errors.nees is not None:
        figures["two_sigma_share"] = float(np.mean(errors.nees <= TWO_SIGMA_NEES))
        figures["nees_mean"] = float(np.mean(errors.nees))
        figures["nees_lower_95"], figures["nees_upper_95"] = mean_nees_bounds(_independent(errors.time_s), 2)
    return figures


def _independent(time_s: np.ndarray) -> int:
    """How many of the samples are at least INDEPENDENT_INTERVAL_S apart (consistency.py: N of the NEES bounds)."""
    return len(decimated(time_s))


def _errors(points: np.ndarray, covariance: np.ndarray | None, series: TrackSeries, reference: ReferenceTrack,
            offset_s: float) -> ErrorSeries:
    return error_series(points, covariance, series, reference, _inside(series, reference, offset_s), offset_s)


def score_series(series: TrackSeries, reference: ReferenceTrack,
                 max_offset_s: float = DEFAULT_MAX_OFFSET_S) -> ReferenceScore:
    """ValueError when no sample of the series lies within the reference's time span."""
    if not _inside(series, reference, 0.0, margin_s=-max_offset_s).any():
        first_s, last_s = reference.span_s()
        raise ValueError(f"{series.name}: no sample within the reference's {first_s:.3f} to {last_s:.3f} s "
                         f"(give both on one time base)")
    points, covariance = _compared_points(series, reference)
    offset_s = best_fit_offset_s(points, series, reference, max_offset_s)
    errors = _errors(points, covariance, series, reference, offset_s)
    best = _figures(errors)
    return ReferenceScore(series.name, best["samples"], offset_s, best,
                          _figures(_errors(points, covariance, series, reference, 0.0)), errors)
