"""How far a ratio of two percentiles may move by its sampling alone: the half-width of its 95 % bootstrap interval.

A p99 of a few hundred latencies rests on its few largest samples, so two runs of the same code differ by a fifth
(bench_gateway_ws: +24 % between two quiet runs of one commit). scipy's bootstrap resamples each condition's
latencies (percentile method, Efron and Tibshirani 1993, ch. 13) and gives the interval of the ratio; its
half-width over the ratio is the figure's `spread` (bench/figure.py). Resampling single latencies treats them as
independent, which neighbouring steps of a loaded machine are not: the interval is, if anything, too narrow.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import bootstrap

CONFIDENCE = 0.95
RESAMPLES = 2000
# The same resamples in every run, so that a figure's spread moves only with its samples.
SEED = 20261207
# Fewer samples than this give no interval worth the name (a p99 of them is their largest).
MIN_SAMPLES = 100


def percentile_ratio_spread(baseline: np.ndarray, measured: np.ndarray, percentile: float) -> float | None:
    """The half-width of the 95 % interval of percentile(measured) / percentile(baseline), over that ratio; None
    when the samples are too few to give one (a smoke run's)."""

    def ratio(baseline_sample: np.ndarray, measured_sample: np.ndarray, axis: int = -1) -> np.ndarray:
        return (np.percentile(measured_sample, percentile, axis=axis)
                / np.percentile(baseline_sample, percentile, axis=axis))

    value = float(ratio(baseline, measured))
    if min(baseline.size, measured.size) < MIN_SAMPLES or not np.isfinite(value) or value <= 0:
        return None
    interval = bootstrap((baseline, measured), ratio, vectorized=True, paired=False, confidence_level=CONFIDENCE,
                         n_resamples=RESAMPLES, method="percentile", random_state=np.random.default_rng(SEED))
    low, high = interval.confidence_interval
    spread = float(max(high / value - 1, 1 - low / value))
    return spread if np.isfinite(spread) else None
