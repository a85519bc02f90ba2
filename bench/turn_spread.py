"""How far a ratio measured in turns about may move by the machine alone: the half-width of the 95 % interval of
the mean of its per-turn ratios, over that mean (a figure's `spread`, bench/figure.py).

Each turn measures both sides of the ratio back to back, so each turn gives one ratio; the turns of one run differ
by what the shared machine did meanwhile, and their spread is an estimate of how far a second run may land. The
interval is Student's t for the mean of a small sample (n - 1 degrees of freedom): with 3 turns its half-width is
2.5 standard deviations of the turns' ratios. Fewer than MIN_TURNS turns give no interval (a smoke run's one turn).
Turns of one run share that run's load, so the interval is, if anything, too narrow for a second run made at
another hour.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence

from scipy.stats import t as student_t

CONFIDENCE = 0.95
MIN_TURNS = 3


def turn_ratio_spread(numerators: Sequence[float], denominators: Sequence[float]) -> float | None:
    """numerators[i] / denominators[i] is turn i's ratio; the half-width of the 95 % interval of their mean over
    that mean, or None with fewer than MIN_TURNS turns or a turn that measured nothing."""
    if len(numerators) != len(denominators):
        raise ValueError(f"{len(numerators)} numerators for {len(denominators)} denominators: one of each per turn")
    ratios = [n / d for n, d in zip(numerators, denominators) if d > 0 and math.isfinite(n / d)]
    if len(ratios) < MIN_TURNS or len(ratios) < len(numerators):
        return None
    mean = statistics.fmean(ratios)
    if mean <= 0:
        return None
    critical = float(student_t.ppf(0.5 + CONFIDENCE / 2, len(ratios) - 1))
    return critical * statistics.stdev(ratios) / math.sqrt(len(ratios)) / mean
