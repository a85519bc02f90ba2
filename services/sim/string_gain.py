"""The string gain (Ploeg et al.: the amplification of a speed oscillation along a platoon), per pair of consecutive
vehicles and the largest, over a judged window: of our runs (services/sim/metrics.py's judge) and of a baseline's
speeds alike (coopdrive/launch/plexe_baseline.py)."""

from __future__ import annotations

import math
from typing import Collection, Sequence

import numpy as np

MIN_STRING_AMPLITUDE_MPS = 0.05


def speed_amplitude(speed_mps: np.ndarray, time_s: np.ndarray | None = None,
                    frequency_hz: float | None = None) -> float:
    """Amplitude of the detrended speed.

    With the excitation frequency known, a least-squares fit of offset, linear trend and sinusoid gives the
    exact amplitude of a sinusoid on a trend; otherwise half the peak-to-peak of the linearly detrended speed
    (a detrended whole number of sine periods keeps a small slope bias that cancels in ratios).
    """
    values = np.asarray(speed_mps, dtype=float)
    times = np.arange(values.size, dtype=float) if time_s is None else np.asarray(time_s, dtype=float)
    valid = np.isfinite(values)
    values, times = values[valid], times[valid]
    if values.size < 2:
        return 0.0
    if frequency_hz is not None:
        omega = 2.0 * math.pi * frequency_hz
        basis = np.column_stack((np.ones_like(times), times - times.mean(), np.sin(omega * times),
                                 np.cos(omega * times)))
        coefficients, *_ = np.linalg.lstsq(basis, values, rcond=None)
        return float(math.hypot(coefficients[2], coefficients[3]))
    slope, offset = np.polyfit(times, values, 1)
    detrended = values - (slope * times + offset)
    return float(detrended.max() - detrended.min()) / 2.0


def string_gains(speeds_mps: Sequence[np.ndarray], time_s: np.ndarray | None = None,
                 frequency_hz: float | None = None) -> list[float]:
    """Per pair of consecutive vehicles (leader first), the ratio of follower to predecessor speed amplitude; NaN for
    a pair whose predecessor's speed hardly varies (it excites nothing: the ratio would be noise over noise)."""
    amplitudes = [speed_amplitude(s, time_s, frequency_hz) for s in speeds_mps]
    return [b / a if a > MIN_STRING_AMPLITUDE_MPS else math.nan for a, b in zip(amplitudes, amplitudes[1:])]


def string_gain(speeds_mps: Sequence[np.ndarray], time_s: np.ndarray | None = None,
                frequency_hz: float | None = None) -> float:
    """Max over consecutive vehicles (leader first) of the ratio of follower to predecessor speed amplitude."""
    ratios = [gain for gain in string_gains(speeds_mps, time_s, frequency_hz) if not math.isnan(gain)]
    return max(ratios) if ratios else math.nan


PAIR_GAIN_PREFIX = "string_gain_pair_"


def pair_gain_key(follower_index: int) -> str:
    """The metric of one pair's string gain: the platoon's follower_index-th vehicle (1 = the leader's follower)
    behind its predecessor."""
    return f"{PAIR_GAIN_PREFIX}{follower_index}"


def pair_gain_keys(metrics: Collection[str]) -> list[str]:
    """The pairs' string gains among these metric names, the leader's pair first."""
    pairs = [key for key in metrics if key.startswith(PAIR_GAIN_PREFIX)]
    return sorted(pairs, key=lambda key: int(key.removeprefix(PAIR_GAIN_PREFIX)))


def judged_string_gains(time_s: np.ndarray, speeds_mps: Sequence[np.ndarray], start_s: float, end_s: float,
                        frequency_hz: float | None) -> dict[str, float]:
    """string_gain and each pair's over the judged window [start_s, end_s) of speeds sampled at time_s, leader
    first; nothing for a run that does not cover the window or a platoon of one."""
    if len(speeds_mps) < 2 or not _covers(time_s, end_s):
        return {}
    window = (time_s >= start_s) & (time_s < end_s)
    gains = string_gains([np.asarray(speed)[window] for speed in speeds_mps], time_s[window], frequency_hz)
    finite = [gain for gain in gains if not math.isnan(gain)]
    return {"string_gain": max(finite) if finite else math.nan,
            **{pair_gain_key(index): gain for index, gain in enumerate(gains, start=1)}}


def _covers(time_s: np.ndarray, end_s: float) -> bool:
    """Whether the truth reaches end_s to within its own sample period. A run cut short (`--duration`) inside the
    judged oscillation has seen only its onset, where a follower's transient can outswing its predecessor: its
    ratio is not the string gain (string 20 s of 60: 1.075, where the whole window gives below 1)."""
    if not math.isfinite(end_s):
        return True
    period_s = float(time_s[-1] - time_s[-2]) if len(time_s) >= 2 else 0.0
    return len(time_s) > 0 and time_s[-1] + period_s >= end_s
