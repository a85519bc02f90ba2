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
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

# Cost of a pair outside the gate; large but finite so the solver always has a feasible matrix.
_FORBIDDEN = 1e9
_MIN_RANGE_M = 1e-3
# Below this many measurement-track pairs one dense cost matrix is cheaper than finding groups.
DENSE_PAIRS_MAX = 2500
# The groups' Euclidean radius is the gate's for the widest covariance, times this: the gate is taken in range
# and bearing (the bearing residual weighted up), which a plane distance only approximates at short range.
_GROUP_RADIUS_MARGIN = 1.5


def _largest_eigenvalues(cov: np.ndarray) -> np.ndarray:
    """Largest eigenvalue of each symmetric 2x2 matrix of cov (K, 2, 2)."""
    half_trace = 0.5 * (cov[:, 0, 0] + cov[:, 1, 1])
    half_difference = 0.5 * (cov[:, 0, 0] - cov[:, 1, 1])
    off = 0.5 * (cov[:, 0, 1] + cov[:, 1, 0])
    return half_trace + np.sqrt(half_difference**2 + off**2)


def gate_groups(meas_xy: np.ndarray, meas_cov: np.ndarray, origins_xy: np.ndarray, track_xy: np.ndarray,
                track_cov: np.ndarray, gate: float, angle_emphasis: float,
                dense_pairs_max: int = DENSE_PAIRS_MAX) -> list[tuple[np.ndarray, np.ndarray]]:
    """Measurements and tracks split into groups that no gated pair crosses: (measurement indices, track
    indices) per group, a measurement near no track alone in its own; few pairs make one group. Assigning each
    group on its own gives the joint assignment's pairs, and the cost grows as n log n with the objects instead
    of n^2 (see gated_pairs); the groups are the connected components of the gated pairs."""
    n, m = len(meas_xy), len(track_xy)
    if m == 0:
        return [(np.array([i]), np.zeros(0, dtype=int)) for i in range(n)]
    if n * m <= dense_pairs_max:
        return [(np.arange(n), np.arange(m))]
    meas_of_pairs, tracks_of_pairs, _, _ = gated_pairs(meas_xy, meas_cov, origins_xy, track_xy, track_cov, gate,
                                                       angle_emphasis)
    count, labels = pair_components(meas_of_pairs, tracks_of_pairs, n, m)
    order = np.argsort(labels, kind="stable")
    bounds = np.searchsorted(labels[order], np.arange(count + 1))
    groups = []
    for start, end in zip(bounds[:-1], bounds[1:]):
        members = order[start:end]
        measurements = members[members < n]
        if measurements.size:
            groups.append((measurements, members[members >= n] - n))
    return groups


def gated_pairs(meas_xy: np.ndarray, meas_cov: np.ndarray, origins_xy: np.ndarray, track_xy: np.ndarray,
                track_cov: np.ndarray, gate: float, angle_emphasis: float) -> tuple[np.ndarray, ...]:
    """Every (measurement, track) pair inside the gate, with its d^2 and innovation log-determinant: a kd-tree
    finds the pairs within a conservative plane distance of each track (its gate with the widest measurement
    covariance), and the gate itself keeps those whose range-bearing cost is inside it."""
    meas_of_pairs, tracks_of_pairs = _near_pairs(meas_xy, meas_cov, track_xy, track_cov, gate)
    d2, log_det = polar_cost_pairs(meas_xy[meas_of_pairs], meas_cov[meas_of_pairs], origins_xy[meas_of_pairs],
                                   track_xy[tracks_of_pairs], track_cov[tracks_of_pairs], angle_emphasis)
    inside = d2 <= gate
    return meas_of_pairs[inside], tracks_of_pairs[inside], d2[inside], log_det[inside]


def pair_components(meas_of_pairs: np.ndarray, tracks_of_pairs: np.ndarray, n: int, m: int) -> tuple[int, np.ndarray]:
    """Connected components of n measurements and m tracks joined by pairs: their count and each node's label,
    nodes 0..n-1 being the measurements and n..n+m-1 the tracks."""
    graph = coo_matrix((np.ones(meas_of_pairs.size), (meas_of_pairs, n + tracks_of_pairs)), shape=(n + m, n + m))
    return connected_components(graph, directed=False)


def _near_pairs(meas_xy, meas_cov, track_xy, track_cov, gate) -> tuple[np.ndarray, np.ndarray]:
    """(measurement, track) index pairs closer in the plane than the track's conservative gate radius."""
    widest_meas = float(_largest_eigenvalues(meas_cov).max())
    radii_m = _GROUP_RADIUS_MARGIN * np.sqrt(gate * (_largest_eigenvalues(track_cov) + widest_meas))
    # Every pair within the largest radius in one call (the kd-trees' own loop), then each track's own radius.
    near = cKDTree(meas_xy).sparse_distance_matrix(cKDTree(track_xy), float(radii_m.max()), output_type="ndarray")
    within = near["v"] <= radii_m[near["j"]]
    return near["i"][within].astype(int), near["j"][within].astype(int)


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
    d2, log_det = _polar_costs(meas_xy[:, None, :], meas_cov[:, None], origins_xy[:, None, :], track_xy[None, :, :],
                               track_cov[None, :], angle_emphasis)
    return (d2, log_det) if with_log_det else d2


def polar_cost_pairs(meas_xy: np.ndarray, meas_cov: np.ndarray, origins_xy: np.ndarray, track_xy: np.ndarray,
                     track_cov: np.ndarray, angle_emphasis: float) -> tuple[np.ndarray, np.ndarray]:
    """polar_cost_matrix's d^2 and log-determinant for K given pairs (row k: measurement k with track k)."""
    if len(meas_xy) == 0:
        return np.zeros(0), np.zeros(0)
    return _polar_costs(meas_xy, meas_cov, origins_xy, track_xy, track_cov, angle_emphasis)


def _polar_costs(meas_xy, meas_cov, origins_xy, track_xy, track_cov, angle_emphasis):
    """d^2 and ln|S| of measurements against tracks, for any shapes that broadcast ((..., 2), (..., 2, 2))."""
    rel_t = track_xy - origins_xy
    rel_m = meas_xy - origins_xy
    r_t = np.maximum(np.linalg.norm(rel_t, axis=-1), _MIN_RANGE_M)
    r_m = np.linalg.norm(rel_m, axis=-1)
    th_t = np.arctan2(rel_t[..., 1], rel_t[..., 0])
    th_m = np.arctan2(rel_m[..., 1], rel_m[..., 0])
    d_range = r_m - r_t
    d_bearing = (th_m - th_t + math.pi) % (2.0 * math.pi) - math.pi
    d_bearing = d_bearing * math.sqrt(angle_emphasis)
    # S = J (P + R) J^T with J the Jacobian of (range, bearing) w.r.t. (x, y) at the predicted track,
    # written out per element: numpy's batched matmul is slow on millions of 2x2 blocks.
    ja, jb = rel_t[..., 0] / r_t, rel_t[..., 1] / r_t
    jc, jd = -jb / r_t, ja / r_t
    t00 = track_cov[..., 0, 0] + meas_cov[..., 0, 0]
    t01 = 0.5 * (track_cov[..., 0, 1] + track_cov[..., 1, 0] + meas_cov[..., 0, 1] + meas_cov[..., 1, 0])
    t11 = track_cov[..., 1, 1] + meas_cov[..., 1, 1]
    a = ja * ja * t00 + 2.0 * ja * jb * t01 + jb * jb * t11
    b = ja * jc * t00 + (ja * jd + jb * jc) * t01 + jb * jd * t11
    d = jc * jc * t00 + 2.0 * jc * jd * t01 + jd * jd * t11
    det = np.maximum(a * d - b * b, 1e-12)
    d2 = (d * d_range**2 - 2.0 * b * d_range * d_bearing + a * d_bearing**2) / det
    return d2, np.log(det)


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
