"""How well each stack knew where it was: its ego states and GNSS fixes against the simulator's truth.

Figures, pooled over the stack vehicles:
- position_rmse_precise_m: the estimate's horizontal RMS error while it fused RTK-fixed solutions;
  gnss_fix_rmse_m the raw RTK-fixed fixes' own, and gnss_noise_rms_m the noise the receiver reported for them
  (GST sigmas, 2D RMS); position_rmse_over_gnss_noise the ratio of the first and the last.
- position_nees_2sigma_fraction: share of estimates whose true position lies inside their 2-sigma ellipse
  (normalised estimation error squared within the chi-square bound of probability 0.9545, two degrees of freedom).
- outage_position_error_max_m: the largest error while the receiver reported no fix.
- gnss_jump_position_error_max_m: the largest error while fixes were off by far more than their noise (multipath)
  and for a second after.
- lane_index_accuracy: share of all estimates matched to the true lane (unmatched ones count as wrong), outside
  lane changes.

The simulator's antenna sits at the vehicle reference point, where the truth and the estimate are, so the fixes
are compared with the truth there. Fixes are placed in the local frame through the nearest ego state's own
geodetic position, so no map origin is needed.
"""

from __future__ import annotations

import math

import numpy as np
import pymap3d

from coopdrive.judging.run_messages import RunMessages
from coopdrive.services.geolocation.ekf import chi2_quantile
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import ego_pb2, gnss_pb2

TWO_SIGMA_PROBABILITY = 0.9545
NEES_BOUND = chi2_quantile(TWO_SIGMA_PROBABILITY, 2)
# A fix further off the truth than this many of its reported sigmas, and at least JUMP_MIN_M, is a jump.
JUMP_SIGMAS = 5.0
JUMP_MIN_M = 2.0
JUMP_AFTERMATH_S = 1.0
# The true lane must stay the same this long before and after a sample for it to count outside lane changes.
LANE_STEADY_S = 2.0
STATE_SIZE = 6


def _truth_xy_at(series: TruthSeries, vehicle_id: str, time_s: np.ndarray) -> np.ndarray:
    x, y = series.get(vehicle_id, "x_m"), series.get(vehicle_id, "y_m")
    present = np.isfinite(x)
    return np.column_stack((np.interp(time_s, series.time_s[present], x[present], left=np.nan, right=np.nan),
                            np.interp(time_s, series.time_s[present], y[present], left=np.nan, right=np.nan)))


def _steady_lane(series: TruthSeries, vehicle_id: str) -> np.ndarray:
    """Per truth sample: its lane index where that lane held LANE_STEADY_S either side, else -1."""
    lanes = series.get(vehicle_id, "lane_index")
    steady = lanes.copy()
    for index, time_s in enumerate(series.time_s):
        window = lanes[(series.time_s >= time_s - LANE_STEADY_S) & (series.time_s <= time_s + LANE_STEADY_S)]
        if not np.all(window == lanes[index]):
            steady[index] = -1
    return np.where(np.isfinite(steady), steady, -1)


def _fix_xy(fixes: list[gnss_pb2.GnssFix], states: list[ego_pb2.EgoState], state_time_s: np.ndarray) -> np.ndarray:
    nearest = np.clip(np.searchsorted(state_time_s, [f.header.sample_time_s for f in fixes]), 0, len(states) - 1)
    rows = []
    for fix, index in zip(fixes, nearest):
        state = states[index]
        east_m, north_m, _ = pymap3d.geodetic2enu(fix.latitude_deg, fix.longitude_deg, 0.0,
                                                  state.latitude_deg, state.longitude_deg, 0.0)
        rows.append((state.x_m + east_m, state.y_m + north_m))
    return np.array(rows).reshape(-1, 2)


class _Pool:
    """Squared errors and counts gathered over vehicles."""

    def __init__(self) -> None:
        self.values: dict[str, list[np.ndarray]] = {}

    def add(self, name: str, values: np.ndarray) -> None:
        self.values.setdefault(name, []).append(np.asarray(values, dtype=float))

    def joined(self, name: str) -> np.ndarray:
        return np.concatenate(self.values[name]) if name in self.values else np.empty(0)


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(values ** 2))) if values.size else math.nan


def _in_spans(time_s: np.ndarray, spans: list[tuple[float, float]]) -> np.ndarray:
    inside = np.zeros(time_s.size, dtype=bool)
    for start_s, end_s in spans:
        inside |= (time_s >= start_s) & (time_s <= end_s)
    return inside


def _vehicle(series: TruthSeries, vehicle_id: str, states: list[ego_pb2.EgoState],
             fixes: list[gnss_pb2.GnssFix], pool: _Pool) -> None:
    states = sorted((s for s in states if s.mode != ego_pb2.LOCALISATION_MODE_LOST),
                    key=lambda s: s.header.sample_time_s)
    if not states:
        return
    time_s = np.array([s.header.sample_time_s for s in states])
    estimate = np.array([[s.x_m, s.y_m] for s in states])
    error = estimate - _truth_xy_at(series, vehicle_id, time_s)
    known = np.all(np.isfinite(error), axis=1)
    distance = np.hypot(error[:, 0], error[:, 1])

    precise = np.array([s.mode == ego_pb2.LOCALISATION_MODE_GNSS_PRECISE
                        and s.last_fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED for s in states])
    pool.add("precise_error", distance[known & precise])

    nees = []
    for row, state in zip(error[known], np.array(states, dtype=object)[known]):
        if len(state.covariance) == STATE_SIZE * STATE_SIZE:
            position_cov = np.array(state.covariance).reshape(STATE_SIZE, STATE_SIZE)[:2, :2]
            nees.append(float(row @ np.linalg.solve(position_cov, row)))
    pool.add("nees", np.array(nees))

    fixes = sorted(fixes, key=lambda f: f.header.sample_time_s)
    fix_time_s = np.array([f.header.sample_time_s for f in fixes])
    valid = [f for f in fixes if f.fix_mode != gnss_pb2.FIX_MODE_NO_FIX]
    outage_spans = []
    for fix, next_time_s in zip(fixes, [*fix_time_s[1:], math.inf]):
        if fix.fix_mode == gnss_pb2.FIX_MODE_NO_FIX:
            outage_spans.append((fix.header.sample_time_s, float(next_time_s)))
    pool.add("outage_error", distance[known & _in_spans(time_s, outage_spans)])

    jump_spans = []
    if valid:
        valid_time_s = np.array([f.header.sample_time_s for f in valid])
        fix_error = _fix_xy(valid, states, time_s) - _truth_xy_at(series, vehicle_id, valid_time_s)
        fix_distance = np.hypot(fix_error[:, 0], fix_error[:, 1])
        sigma_2d = np.array([math.hypot(f.std_east_m, f.std_north_m) for f in valid])
        rtk = np.array([f.fix_mode == gnss_pb2.FIX_MODE_RTK_FIXED for f in valid]) & np.isfinite(fix_distance)
        jumped = fix_distance > np.maximum(JUMP_SIGMAS * sigma_2d, JUMP_MIN_M)
        pool.add("fix_error", fix_distance[rtk & ~jumped])
        pool.add("fix_sigma", sigma_2d[rtk & ~jumped & (sigma_2d > 0)])
        jump_spans = [(t, t + JUMP_AFTERMATH_S) for t in valid_time_s[jumped]]
        pool.add("jump_count", np.array([float(np.count_nonzero(jumped))]))
    pool.add("jump_error", distance[known & _in_spans(time_s, jump_spans)])

    lanes = _steady_lane(series, vehicle_id)
    nearest = np.clip(np.searchsorted(series.time_s, time_s), 0, series.time_s.size - 1)
    true_lane = lanes[nearest]
    matched = np.array([s.lane.matched for s in states])
    judged = true_lane >= 0
    estimated_lane = np.array([s.lane.lane_index for s in states])
    # An estimate matched to no lane is a wrong answer, not a sample to leave out.
    pool.add("lane_correct", (matched[judged] & (estimated_lane[judged] == true_lane[judged])).astype(float))


def localisation_metrics(series: TruthSeries, messages: RunMessages) -> dict[str, float]:
    """The figures of the module docstring; a figure with nothing to measure is NaN."""
    pool = _Pool()
    for vehicle_id, states in messages.ego_states.items():
        if vehicle_id in series.values:
            _vehicle(series, vehicle_id, states, messages.gnss_fixes.get(vehicle_id, []), pool)
    nees = pool.joined("nees")
    outage, jump, lanes = pool.joined("outage_error"), pool.joined("jump_error"), pool.joined("lane_correct")
    precise_rmse, noise_rms = _rms(pool.joined("precise_error")), _rms(pool.joined("fix_sigma"))
    return {
        "position_rmse_precise_m": precise_rmse,
        "gnss_fix_rmse_m": _rms(pool.joined("fix_error")),
        "gnss_noise_rms_m": noise_rms,
        "position_rmse_over_gnss_noise": precise_rmse / noise_rms if noise_rms > 0 else math.nan,
        "position_nees_2sigma_fraction": float(np.mean(nees <= NEES_BOUND)) if nees.size else math.nan,
        "outage_position_error_max_m": float(outage.max()) if outage.size else math.nan,
        "gnss_jumps": float(pool.joined("jump_count").sum()),
        "gnss_jump_position_error_max_m": float(jump.max()) if jump.size else math.nan,
        "lane_index_accuracy": float(lanes.mean()) if lanes.size else math.nan,
    }
