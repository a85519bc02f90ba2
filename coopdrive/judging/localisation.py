"""How well each stack knew where it was: its ego states and GNSS fixes against the simulator's truth.

Figures, pooled over the stack vehicles (errors are horizontal, estimate minus truth; RMS of their length):
- position_rmse_precise_m: the estimate's RMS error while it fused RTK-fixed solutions.
- gnss_fix_rmse_m: the raw fixes' own RMS error, every fix with a position (none left out), at the time the stack
  stamped them; gnss_fix_rmse_<mode>_m and position_rmse_<mode>_m the same per fix mode (for the estimate: the
  mode of the last fix it fused), for each mode the run saw (rtk_fixed, rtk_float, dgps, sbas, single).
- position_rmse_over_gnss_fix_rmse: the judge's position_rmse_m over gnss_fix_rmse_m, both against the truth:
  below 1, fusion makes the receiver better. gnss_noise_rms_m: the noise the receiver claimed for its RTK-fixed
  fixes (GST sigmas, 2D RMS), to set beside their real error.
- position_2sigma_share, position_nees_mean, position_nees_mean_1hz, position_nees_samples_1hz and the bounds
  position_nees_lower_95 / position_nees_upper_95: the 2-D position NEES and its chi-square test
  (coopdrive/judging/consistency.py): a consistent estimate has 86.5 % inside its 2-sigma ellipse and an
  average NEES of 2, within the bounds.
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

from coopdrive.judging.consistency import consistency_figures, decimated, nees
from coopdrive.judging.run_messages import RunMessages
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import ego_pb2, gnss_pb2

# The fix modes figures are given for, by their names in the keys.
FIX_MODE_NAMES = {gnss_pb2.FIX_MODE_RTK_FIXED: "rtk_fixed", gnss_pb2.FIX_MODE_RTK_FLOAT: "rtk_float",
                  gnss_pb2.FIX_MODE_DGPS: "dgps", gnss_pb2.FIX_MODE_SBAS: "sbas", gnss_pb2.FIX_MODE_SINGLE: "single"}
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


def _add_nees(states: list[ego_pb2.EgoState], time_s: np.ndarray, error: np.ndarray, known: np.ndarray,
              pool: _Pool) -> None:
    """Every estimate's NEES, and those of the estimates a second apart (consistency.py)."""
    with_covariance = [index for index in np.flatnonzero(known)
                       if len(states[index].covariance) == STATE_SIZE * STATE_SIZE]
    covariance = np.array([np.array(states[i].covariance).reshape(STATE_SIZE, STATE_SIZE)[:2, :2]
                           for i in with_covariance]).reshape(-1, 2, 2)
    values = nees(error[with_covariance], covariance)
    pool.add("nees", values)
    pool.add("nees_1hz", values[decimated(time_s[with_covariance])])


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

    _add_nees(states, time_s, error, known, pool)
    last_mode = np.array([s.last_fix_mode for s in states])
    for mode, name in FIX_MODE_NAMES.items():
        pool.add(f"position_error_{name}", distance[known & (last_mode == mode)])

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
        modes = np.array([f.fix_mode for f in valid])
        rtk = (modes == gnss_pb2.FIX_MODE_RTK_FIXED) & np.isfinite(fix_distance)
        jumped = fix_distance > np.maximum(JUMP_SIGMAS * sigma_2d, JUMP_MIN_M)
        pool.add("fix_error", fix_distance[np.isfinite(fix_distance)])
        for mode, name in FIX_MODE_NAMES.items():
            pool.add(f"fix_error_{name}", fix_distance[np.isfinite(fix_distance) & (modes == mode)])
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


def _per_fix_mode(pool: _Pool) -> dict[str, float]:
    figures = {}
    for name in FIX_MODE_NAMES.values():
        fix_error = pool.joined(f"fix_error_{name}")
        if fix_error.size:
            figures[f"gnss_fix_rmse_{name}_m"] = _rms(fix_error)
            figures[f"position_rmse_{name}_m"] = _rms(pool.joined(f"position_error_{name}"))
    return figures


def localisation_metrics(series: TruthSeries, messages: RunMessages,
                         position_rmse_m: float = math.nan) -> dict[str, float]:
    """The figures of the module docstring; a figure with nothing to measure is NaN. position_rmse_m: the judge's
    (services/sim/metrics.py), set beside the fixes'."""
    pool = _Pool()
    for vehicle_id, states in messages.ego_states.items():
        if vehicle_id in series.values:
            _vehicle(series, vehicle_id, states, messages.gnss_fixes.get(vehicle_id, []), pool)
    outage, jump, lanes = pool.joined("outage_error"), pool.joined("jump_error"), pool.joined("lane_correct")
    fix_rmse = _rms(pool.joined("fix_error"))
    return {
        "position_rmse_precise_m": _rms(pool.joined("precise_error")),
        "gnss_fix_rmse_m": fix_rmse,
        "gnss_noise_rms_m": _rms(pool.joined("fix_sigma")),
        "position_rmse_over_gnss_fix_rmse": position_rmse_m / fix_rmse if fix_rmse > 0 else math.nan,
        **_per_fix_mode(pool),
        **consistency_figures(pool.joined("nees"), pool.joined("nees_1hz"), 2, "position"),
        "outage_position_error_max_m": float(outage.max()) if outage.size else math.nan,
        "gnss_jumps": float(pool.joined("jump_count").sum()),
        "gnss_jump_position_error_max_m": float(jump.max()) if jump.size else math.nan,
        "lane_index_accuracy": float(lanes.mean()) if lanes.size else math.nan,
    }
