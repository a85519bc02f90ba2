"""Whether an estimate's covariance describes its error: the normalised estimation error squared (NEES) and its
chi-square test, as Bar-Shalom, Li and Kirubarajan define them (Estimation with Applications to Tracking and
Navigation, 5.4.2).

- NEES = e' P^-1 e of an n-dimensional error e with covariance P: chi-square with n degrees of freedom when the
  estimate is consistent (mean n: 2 for a horizontal position).
- The average NEES of N independent samples, times N, is chi-square with N n degrees of freedom: its two-sided
  95 % bounds are chi2(0.025, N n) / N and chi2(0.975, N n) / N (eq. 5.4.2-7 and -8).
- The share of samples inside the estimate's own 2-sigma ellipse (NEES <= 2^2): 1 - exp(-2) = 86.5 % for a
  consistent 2-D estimate (95.45 % is the one-dimensional figure).

Successive estimates of a filter are correlated in time, so N counts samples taken at least `interval_s` apart
(one a second by default), not every published state: with every 20 ms state counted the bounds would be about
seven times narrower than the samples' real information allows. Errors correlated for longer still (a receiver's
slowly wandering error, a latency bias) make even these bounds too narrow: the test is then strict, not lenient.
"""

from __future__ import annotations

import math

import numpy as np

from coopdrive.services.geolocation.ekf import chi2_quantile

TWO_SIGMA_NEES = 2.0**2
CONSISTENT_TWO_SIGMA_SHARE = 1.0 - math.exp(-2.0)
BOUND_PROBABILITY = 0.95
INDEPENDENT_INTERVAL_S = 1.0


def nees(errors: np.ndarray, covariances: np.ndarray) -> np.ndarray:
    """(n,) NEES of (n, d) errors with their (n, d, d) covariances."""
    if not len(errors):
        return np.empty(0)
    solved = np.linalg.solve(covariances, errors[..., None])[..., 0]
    return np.einsum("ij,ij->i", errors, solved)


def mean_nees_bounds(samples: int, dof: int, probability: float = BOUND_PROBABILITY) -> tuple[float, float]:
    """Two-sided bounds on the average NEES of `samples` independent samples of `dof` dimensions."""
    if samples <= 0:
        return math.nan, math.nan
    tail = (1.0 - probability) / 2.0
    return (chi2_quantile(tail, samples * dof) / samples, chi2_quantile(1.0 - tail, samples * dof) / samples)


def decimated(time_s: np.ndarray, interval_s: float = INDEPENDENT_INTERVAL_S) -> np.ndarray:
    """Indices of samples at least interval_s apart (time-ordered input), the first sample first."""
    kept, next_s = [], -math.inf
    for index, t in enumerate(time_s):
        if t >= next_s:
            kept.append(index)
            next_s = t + interval_s
    return np.array(kept, dtype=int)


def consistency_figures(values: np.ndarray, independent: np.ndarray, dof: int, prefix: str) -> dict[str, float]:
    """`values`: every sample's NEES; `independent`: those at least INDEPENDENT_INTERVAL_S apart. The keys:
    {prefix}_2sigma_share, {prefix}_nees_mean, {prefix}_nees_mean_1hz and its bounds {prefix}_nees_lower_95 and
    {prefix}_nees_upper_95 for {prefix}_nees_samples_1hz samples."""
    lower, upper = mean_nees_bounds(len(independent), dof)
    return {f"{prefix}_2sigma_share": float(np.mean(values <= TWO_SIGMA_NEES)) if len(values) else math.nan,
            f"{prefix}_nees_mean": float(np.mean(values)) if len(values) else math.nan,
            f"{prefix}_nees_mean_1hz": float(np.mean(independent)) if len(independent) else math.nan,
            f"{prefix}_nees_samples_1hz": float(len(independent)),
            f"{prefix}_nees_lower_95": lower, f"{prefix}_nees_upper_95": upper}
