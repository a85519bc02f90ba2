"""A radar reading gates with a track on its range rate as well as on where it is.

A radar measures each target's range rate, and a reading whose range rate the track cannot have is not that
track's, wherever it lies (range-rate gating: Bar-Shalom, Willett and Tian, "Tracking and Data Fusion", 2011,
ch. 3; every automotive radar tracker does it). The innovation of the radial speed, the track's velocity
predicted to the reading's time along the reading's line of sight, has variance los' P_v los + sigma_rr^2;
a pair is forbidden beyond doppler_gate_chi2 of it and doppler_gate_min_mps (a track's speed lags a hard brake's
onset by more than its covariance says), and within the gate its d^2 + ln(variance) adds to the pair's
likelihood cost, as the position's does. Gated on position alone, a stationary false alarm that fell on the rear of
the car ahead in string seed 3 took that car's track from its own reading in the same scan (range rate 0.1 m/s
against 22.1): the track's speed fell 2.7 m/s and its position 0.6 m, the gap v7 measured shrank 0.77 m in one
frame, and v7 braked to -2.0 m/s2 where v6 braked to -0.75 (v6 to v7 amplitude ratio 0.956).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .measurement import Measurement
from .measurement_model import line_of_sight

# (measurement indices, track indices) of a frame's pairs -> (the cost each adds to its likelihood cost, whether
# each may pair at all).
PairTerms = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def range_rate_terms(measurements: list[Measurement], velocity_mps: np.ndarray, velocity_cov: np.ndarray,
                     gate_chi2: float, gate_min_mps: float) -> PairTerms | None:
    """The pair terms of one frame's readings against tracks whose velocities at the frame's time are velocity_mps
    (M, 2), to covariance velocity_cov (M, 2, 2); None when no reading has a range rate."""
    radial = np.array([m.radial_speed_mps is not None for m in measurements])
    if not radial.any():
        return None
    speed_mps = np.array([m.radial_speed_mps if m.radial_speed_mps is not None else 0.0 for m in measurements])
    speed_var = np.array([m.radial_speed_std_mps ** 2 for m in measurements])
    los = np.array([line_of_sight(m) for m in measurements])

    def terms(meas_of: np.ndarray, track_of: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        sight = los[meas_of]
        predicted_mps = np.einsum("ki,ki->k", sight, velocity_mps[track_of])
        variance = np.einsum("ki,kij,kj->k", sight, velocity_cov[track_of], sight) + speed_var[meas_of]
        variance = np.maximum(variance, 1e-9)
        residual_mps = speed_mps[meas_of] - predicted_mps
        d2 = residual_mps ** 2 / variance
        has = radial[meas_of]
        allowed = ~has | (d2 <= gate_chi2) | (np.abs(residual_mps) <= gate_min_mps)
        return np.where(has, d2 + np.log(variance), 0.0), allowed

    return terms
