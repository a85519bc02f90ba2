"""The error processes of a GNSS receiver besides its white noise: a time-correlated (first-order Gauss-Markov)
position error, episodes that lose the configured fix mode, and multipath episodes (jumps, and outages beside
tall vehicles).

Events are Poisson: an episode starts within a sample interval dt with probability 1 - exp(-rate dt) and lasts
an exponential time. Nothing is drawn for a process whose rate is zero, so the ideal world's noise sequence does
not depend on the processes it switches off.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coopdrive.services.sim.sensor_config import GnssConfig
from coopdrive.v1 import gnss_pb2

SECONDS_PER_HOUR = 3600.0
# Share of degradation episodes that fall two modes (RTK fixed to DGPS) rather than one (to RTK float).
DEGRADE_TWO_MODES_SHARE = 0.3
# A multipath jump is between these fractions of multipath_jump_m, in a uniformly random direction.
MULTIPATH_JUMP_SPREAD = (0.5, 1.5)
# Fix modes from worst to best; a degradation episode moves down this list, never below SINGLE.
_MODE_ORDER = [gnss_pb2.FIX_MODE_SINGLE, gnss_pb2.FIX_MODE_SBAS, gnss_pb2.FIX_MODE_DGPS,
               gnss_pb2.FIX_MODE_RTK_FLOAT, gnss_pb2.FIX_MODE_RTK_FIXED]


def degraded(mode: int, steps: int) -> int:
    if mode not in _MODE_ORDER:
        return mode
    return _MODE_ORDER[max(_MODE_ORDER.index(mode) - steps, 0)]


def episode_starts(rng: np.random.Generator, rate_per_h: float, dt_s: float) -> bool:
    return rng.random() < -math.expm1(-rate_per_h / SECONDS_PER_HOUR * dt_s)


@dataclass
class _Episode:
    end_s: float
    east_m: float = 0.0
    north_m: float = 0.0
    outage: bool = False
    steps: int = 0


class GaussMarkovError:
    """Unit-variance first-order Gauss-Markov noise per axis, scaled by the caller: a fix-mode change then
    changes the error's size at once, as a receiver's solution jumps when it gains or loses RTK."""

    def __init__(self, rng: np.random.Generator, correlation_time_s: float, axes: int = 3) -> None:
        self.rng = rng
        self.correlation_time_s = correlation_time_s
        self.state = np.zeros(axes)
        self._last_s: float | None = None

    def sample(self, time_s: float) -> np.ndarray:
        tau_s = self.correlation_time_s
        phi = math.exp(-(time_s - self._last_s) / tau_s) if tau_s > 0.0 and self._last_s is not None else 0.0
        self._last_s = time_s
        self.state = phi * self.state + math.sqrt(1.0 - phi * phi) * self.rng.standard_normal(self.state.size)
        return self.state


class GnssEpisodes:
    """Fix-mode degradation and multipath episodes of one receiver."""

    def __init__(self, config: GnssConfig, rng: np.random.Generator) -> None:
        self.config = config
        self.rng = rng
        self._degradation: _Episode | None = None
        self._multipath: _Episode | None = None
        self._last_s: float | None = None

    def update(self, time_s: float, near_obstacle: bool) -> None:
        dt_s = 0.0 if self._last_s is None else time_s - self._last_s
        self._last_s = time_s
        self._degradation = self._next_degradation(time_s, dt_s)
        self._multipath = self._next_multipath(time_s, dt_s, near_obstacle)

    def mode(self, nominal_mode: int) -> int:
        episode = self._degradation
        return nominal_mode if episode is None else degraded(nominal_mode, episode.steps)

    @property
    def outage(self) -> bool:
        return self._multipath is not None and self._multipath.outage

    @property
    def offset_m(self) -> tuple[float, float]:
        episode = self._multipath
        return (0.0, 0.0) if episode is None else (episode.east_m, episode.north_m)

    def _duration_s(self, mean_s: float) -> float:
        return float(self.rng.exponential(mean_s))

    def _next_degradation(self, time_s: float, dt_s: float) -> _Episode | None:
        cfg = self.config
        if self._degradation is not None and time_s < self._degradation.end_s:
            return self._degradation
        if cfg.degradation_rate_per_h <= 0.0 or not episode_starts(self.rng, cfg.degradation_rate_per_h, dt_s):
            return None
        steps = 2 if self.rng.random() < DEGRADE_TWO_MODES_SHARE else 1
        return _Episode(time_s + self._duration_s(cfg.degradation_mean_duration_s), steps=steps)

    def _next_multipath(self, time_s: float, dt_s: float, near_obstacle: bool) -> _Episode | None:
        cfg = self.config
        if self._multipath is not None and time_s < self._multipath.end_s:
            return self._multipath
        rate_per_h = cfg.multipath_near_obstacle_rate_per_h if near_obstacle else cfg.multipath_rate_per_h
        if rate_per_h <= 0.0 or not episode_starts(self.rng, rate_per_h, dt_s):
            return None
        end_s = time_s + self._duration_s(cfg.multipath_mean_duration_s)
        if near_obstacle and self.rng.random() < cfg.near_obstacle_outage_share:
            return _Episode(end_s, outage=True)
        east_m, north_m = jump_offset_m(self.rng, cfg.multipath_jump_m)
        return _Episode(end_s, east_m, north_m)


def jump_offset_m(rng: np.random.Generator, size_m: float) -> tuple[float, float]:
    """A multipath jump: MULTIPATH_JUMP_SPREAD times size_m, in a uniformly random direction."""
    magnitude_m = size_m * rng.uniform(*MULTIPATH_JUMP_SPREAD)
    direction = rng.uniform(0.0, math.tau)
    return magnitude_m * math.cos(direction), magnitude_m * math.sin(direction)
