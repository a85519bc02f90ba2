"""One frame's joint assignment of measurements to tracks, solved per group of measurements and tracks that gate
with each other only (association.py has the gate, its costs and the solver).

Few pairs make one dense cost matrix. Otherwise only the gated pairs are costed (association.gated_pairs), and
a pair whose measurement and track gate with nothing else, most cars seen once, is a match without solving
anything; the rest are solved group by group, each group's matrix holding its gated pairs and forbidding the
others, which gives the pairs of one joint assignment.
"""

from __future__ import annotations

import numpy as np

from .association import DENSE_PAIRS_MAX, assign, gated_pairs, likelihood_cost, pair_components, polar_cost_matrix
from .config import TrackingConfig
from .doppler_gate import PairTerms

# (measurement index, track index, d^2) of every match.
Matches = list[tuple[int, int, float]]
# Up to this many entries the gated pairs left over are solved as one matrix: on a mostly forbidden 200 x 200
# matrix the solver takes a fraction of a millisecond, less than splitting it into its groups costs.
ONE_MATRIX_MAX = 40_000


def associate(meas_xy: np.ndarray, meas_cov: np.ndarray, origins_xy: np.ndarray, track_xy: np.ndarray,
              track_cov: np.ndarray, tracking: TrackingConfig, pair_terms: PairTerms | None = None,
              dense_pairs_max: int = DENSE_PAIRS_MAX,
              one_matrix_max: int = ONE_MATRIX_MAX) -> tuple[Matches, list[int]]:
    """The matches of the joint assignment and the measurements left unmatched. Up to dense_pairs_max
    measurement-track pairs are all costed in one matrix; beyond that, the gated pairs not matched at once are
    solved as one matrix up to one_matrix_max entries, and group by group above. pair_terms, where given, adds
    to each pair's likelihood cost and forbids pairs beyond its own gate (a radar's range rate: doppler_gate.py)."""
    n, m = len(meas_xy), len(track_xy)
    gate, emphasis = tracking.gate_chi2, tracking.angle_emphasis
    if m == 0:
        return [], list(range(n))
    if n * m <= dense_pairs_max:
        d2, log_det = polar_cost_matrix(meas_xy, meas_cov, origins_xy, track_xy, track_cov, emphasis,
                                        with_log_det=True)
        if pair_terms is not None:
            meas_of, track_of = np.indices((n, m))
            more, allowed = pair_terms(meas_of.ravel(), track_of.ravel())
            d2 = np.where(allowed.reshape(n, m), d2, np.inf)
            log_det = log_det + more.reshape(n, m)
        return _solve(np.arange(n), np.arange(m), d2, log_det, gate)
    meas_of, track_of, d2, log_det = gated_pairs(meas_xy, meas_cov, origins_xy, track_xy, track_cov, gate, emphasis)
    if pair_terms is not None:
        more, allowed = pair_terms(meas_of, track_of)
        meas_of, track_of, d2, log_det = meas_of[allowed], track_of[allowed], d2[allowed], (log_det + more)[allowed]
    meas_degree, track_degree = np.bincount(meas_of, minlength=n), np.bincount(track_of, minlength=m)
    alone = (meas_degree[meas_of] == 1) & (track_degree[track_of] == 1)
    matches = list(zip(meas_of[alone].tolist(), track_of[alone].tolist(), d2[alone].tolist(), strict=True))
    unmatched = np.flatnonzero(meas_degree == 0).tolist()
    rest = ~alone
    if rest.any():
        more, left = _solve_groups(meas_of[rest], track_of[rest], d2[rest], log_det[rest], n, m, gate,
                                   one_matrix_max)
        matches += more
        unmatched += left
    return matches, unmatched


def associate_confirmed_first(meas_xy: np.ndarray, meas_cov: np.ndarray, origins_xy: np.ndarray, track_xy: np.ndarray,
                              track_cov: np.ndarray, confirmed: np.ndarray, tracking: TrackingConfig,
                              pair_terms: PairTerms | None = None) -> tuple[Matches, list[int]]:
    """associate() in two rounds: the confirmed tracks (bool mask, one per track) choose among the frame's
    readings first; the tentative tracks take what is left.

    A matching cascade by track standing: a tentative track is a few readings old and its covariance still wide,
    so by likelihood alone it can outbid the car we have tracked for seconds for a reading that car's own,
    noisy one: string seed 4, a camera reading 1 m short of the car ahead went to a radar false alarm beside
    it, which it confirmed, and the car behind braked hard for an object standing in its lane."""
    first, rest = np.flatnonzero(confirmed), np.flatnonzero(~confirmed)
    matches, unmatched = associate(meas_xy, meas_cov, origins_xy, track_xy[first], track_cov[first], tracking,
                                   _among(pair_terms, np.arange(len(meas_xy)), first))
    matches = [(i, int(first[j]), cost) for i, j, cost in matches]
    if rest.size and unmatched:
        left = np.array(sorted(unmatched))
        more, still = associate(meas_xy[left], meas_cov[left], origins_xy[left], track_xy[rest], track_cov[rest],
                                tracking, _among(pair_terms, left, rest))
        matches += [(int(left[i]), int(rest[j]), cost) for i, j, cost in more]
        unmatched = [int(left[i]) for i in still]
    return matches, unmatched


def _among(pair_terms: PairTerms | None, measurements: np.ndarray, tracks: np.ndarray) -> PairTerms | None:
    """pair_terms for a subset of the frame's measurements and tracks, indexed within the subset."""
    if pair_terms is None:
        return None
    return lambda meas_of, track_of: pair_terms(measurements[meas_of], tracks[track_of])


def _solve_groups(meas_of, track_of, d2, log_det, n: int, m: int, gate: float,
                  one_matrix_max: int) -> tuple[Matches, list[int]]:
    """The gated pairs' assignment: one matrix while it stays small, else one per connected group of them."""
    if np.unique(meas_of).size * np.unique(track_of).size <= one_matrix_max:
        return _solve_pairs(meas_of, track_of, d2, log_det, gate)
    _, labels = pair_components(meas_of, track_of, n, m)
    pair_labels = labels[meas_of]
    order = np.argsort(pair_labels, kind="stable")
    matches, unmatched = [], []
    for pairs in np.split(order, np.flatnonzero(np.diff(pair_labels[order])) + 1):
        more, left = _solve_pairs(meas_of[pairs], track_of[pairs], d2[pairs], log_det[pairs], gate)
        matches += more
        unmatched += left
    return matches, unmatched


def _solve_pairs(meas_of, track_of, d2, log_det, gate: float) -> tuple[Matches, list[int]]:
    """Assignment among the given gated pairs: a matrix of their measurements and tracks in which every other
    pair is outside the gate."""
    rows, row_of = np.unique(meas_of, return_inverse=True)
    cols, col_of = np.unique(track_of, return_inverse=True)
    matrix_d2 = np.full((rows.size, cols.size), np.inf)
    matrix_log_det = np.zeros_like(matrix_d2)
    matrix_d2[row_of, col_of], matrix_log_det[row_of, col_of] = d2, log_det
    return _solve(rows, cols, matrix_d2, matrix_log_det, gate)


def _solve(rows: np.ndarray, cols: np.ndarray, d2: np.ndarray, log_det: np.ndarray,
           gate: float) -> tuple[Matches, list[int]]:
    """Assignment of one group by likelihood among the pairs inside the gate; rows and cols are its measurements'
    and tracks' indices in the frame."""
    pairs, left = assign(likelihood_cost(d2, log_det), gate, gate_cost=d2)
    return [(int(rows[i]), int(cols[j]), float(d2[i, j])) for i, j in pairs], [int(rows[i]) for i in left]
