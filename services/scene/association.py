"""Gating and global assignment of measurements to tracks.

Chalmers 4.3.1 matches "by comparing direction and distance ... with a slight emphasis on the
angle". The gate is therefore a Mahalanobis distance in (range, bearing) seen from the sensor, with
the bearing residual weighted by angle_emphasis, and the frame's measurements are assigned jointly
with scipy's linear_sum_assignment so one greedy pick cannot steal another's match.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linear_sum_assignment

# Cost of a pair outside the gate; large but finite so the solver always has a feasible matrix.
_FORBIDDEN = 1e9
_MIN_RANGE_M = 1e-3


def polar_cost_matrix(
    meas_xy: np.ndarray,
    meas_cov: np.ndarray,
    origins_xy: np.ndarray,
    track_xy: np.ndarray,
    track_cov: np.ndarray,
    angle_emphasis: float,
    with_log_det: bool = False,
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Squared Mahalanobis distances (N measurements x M tracks) in range and bearing, and with
    with_log_det the log-determinant of each innovation covariance too."""
    n, m = len(meas_xy), len(track_xy)
    if n == 0 or m == 0:
        return (np.zeros((n, m)), np.zeros((n, m))) if with_log_det else np.zeros((n, m))
    rel_t = track_xy[None, :, :] - origins_xy[:, None, :]  # (N, M, 2)
    rel_m = meas_xy - origins_xy  # (N, 2)
    r_t = np.maximum(np.linalg.norm(rel_t, axis=2), _MIN_RANGE_M)
    r_m = np.linalg.norm(rel_m, axis=1)
    th_t = np.arctan2(rel_t[..., 1], rel_t[..., 0])
    th_m = np.arctan2(rel_m[:, 1], rel_m[:, 0])
    d_range = r_m[:, None] - r_t
    d_bearing = (th_m[:, None] - th_t + math.pi) % (2.0 * math.pi) - math.pi
    d_bearing = d_bearing * math.sqrt(angle_emphasis)
    # S = J (P + R) J^T with J the Jacobian of (range, bearing) w.r.t. (x, y) at the predicted track,
    # written out per element: numpy's batched matmul is slow on millions of 2x2 blocks.
    ja, jb = rel_t[..., 0] / r_t, rel_t[..., 1] / r_t
    jc, jd = -jb / r_t, ja / r_t
    t00 = track_cov[None, :, 0, 0] + meas_cov[:, None, 0, 0]
    t01 = 0.5 * (track_cov[None, :, 0, 1] + track_cov[None, :, 1, 0] + meas_cov[:, None, 0, 1] + meas_cov[:, None, 1, 0])
    t11 = track_cov[None, :, 1, 1] + meas_cov[:, None, 1, 1]
    a = ja * ja * t00 + 2.0 * ja * jb * t01 + jb * jb * t11
    b = ja * jc * t00 + (ja * jd + jb * jc) * t01 + jb * jd * t11
    d = jc * jc * t00 + 2.0 * jc * jd * t01 + jd * jd * t11
    det = np.maximum(a * d - b * b, 1e-12)
    d2 = (d * d_range**2 - 2.0 * b * d_range * d_bearing + a * d_bearing**2) / det
    return (d2, np.log(det)) if with_log_det else d2


def polar_cost_loop(meas_xy, meas_cov, origins_xy, track_xy, track_cov, angle_emphasis, with_log_det=False):
    """The same costs, one pair at a time with a general inverse: the brute-force baseline for bench/."""
    cost = np.zeros((len(meas_xy), len(track_xy)))
    log_det = np.zeros_like(cost)
    for i in range(len(meas_xy)):
        rel_m = meas_xy[i] - origins_xy[i]
        r_m, th_m = np.linalg.norm(rel_m), math.atan2(rel_m[1], rel_m[0])
        for j in range(len(track_xy)):
            rel_t = track_xy[j] - origins_xy[i]
            r_t = max(np.linalg.norm(rel_t), _MIN_RANGE_M)
            th_t = math.atan2(rel_t[1], rel_t[0])
            jac = np.array([[rel_t[0] / r_t, rel_t[1] / r_t], [-rel_t[1] / r_t**2, rel_t[0] / r_t**2]])
            s = jac @ (track_cov[j] + meas_cov[i]) @ jac.T
            bearing = ((th_m - th_t + math.pi) % (2.0 * math.pi) - math.pi) * math.sqrt(angle_emphasis)
            nu = np.array([r_m - r_t, bearing])
            cost[i, j] = float(nu @ np.linalg.inv(s) @ nu)
            log_det[i, j] = math.log(max(np.linalg.det(s), 1e-12))
    return (cost, log_det) if with_log_det else cost


def assign(cost: np.ndarray, gate: float, gate_cost: np.ndarray | None = None) -> tuple[list[tuple[int, int]], list[int]]:
    """Globally optimal pairs (least total cost) among those whose gate_cost (default: cost) is within
    the gate, and the measurements left without a track."""
    n = cost.shape[0]
    if cost.size == 0:
        return [], list(range(n))
    inside = (cost if gate_cost is None else gate_cost) <= gate
    gated = np.where(inside, cost, _FORBIDDEN)
    rows, cols = linear_sum_assignment(gated)
    pairs = [(int(i), int(j)) for i, j in zip(rows, cols, strict=True) if gated[i, j] < _FORBIDDEN]
    matched = {i for i, _ in pairs}
    return pairs, [i for i in range(n) if i not in matched]


def likelihood_cost(d2: np.ndarray, log_det: np.ndarray) -> np.ndarray:
    """Negative log-likelihood up to a constant, d^2 + ln|S|: unlike d^2 alone it does not let a
    vague new track, whose wide covariance makes every distance look small, outbid a sharp
    confirmed track for the same measurement."""
    return d2 + log_det


def match_quality(cost: float, gate: float) -> float:
    """How well a pair matches: 1 for a perfect match, falling linearly to 0.5 at the gate edge."""
    return 1.0 - 0.5 * min(cost, gate) / gate
