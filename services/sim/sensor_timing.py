"""Rate, latency and dropout shared by every simulated sensor, and its seeded random generator."""
from __future__ import annotations

import heapq
import itertools
import math
import zlib
from typing import Any, Callable, Generic, TypeVar

import numpy as np

from coopdrive.services.sim.sensor_config import SensorTimingConfig

Output = TypeVar("Output")
# The sender every simulated sensor's messages name in their header.
SENDER = "sim"

# Tolerance on the sample schedule so that floating-point step times do not skip a sample.
_SCHEDULE_EPS_S = 1e-9


# Mean of a half-normal variable over its scale: sqrt(2 / pi).
HALF_NORMAL_MEAN = math.sqrt(2.0 / math.pi)


def mean_latency_s(config: SensorTimingConfig) -> float:
    """A sensor's mean delivery latency: the fixed part and its half-normal jitter's mean."""
    return config.latency_s + HALF_NORMAL_MEAN * config.latency_jitter_s


def sensor_rng(seed: int, vehicle_id: str, sensor_name: str) -> np.random.Generator:
    """A generator per (run seed, vehicle, sensor): the same seed gives the same noise, whatever else runs."""
    return np.random.default_rng([seed, zlib.crc32(vehicle_id.encode()), zlib.crc32(sensor_name.encode())])


class SensorTiming(Generic[Output]):
    """Samples at rate_hz, drops samples with dropout_probability, delivers the rest latency_s later plus a
    half-normal jitter (never before an earlier sample: a bus keeps one sender's frames in order).

    `poll(now_s, measure)` calls `measure(sample_time_s)` when a sample is due and returns the outputs whose
    delivery time has come, oldest first, as (sample_time_s, delivery_time_s, output).
    """

    def __init__(self, config: SensorTimingConfig, rng: np.random.Generator, start_s: float = 0.0) -> None:
        self.config = config
        self.rng = rng
        self.period_s = 1.0 / config.rate_hz
        self._start_s = start_s
        self._sample_index = 0
        self._next_sample_s = start_s
        self._pending: list[tuple[float, int, float, Any]] = []
        self._last_delivery_s = -float("inf")
        self._order = itertools.count()
        self.forced_dropout = False
        self.samples_taken = 0
        self.samples_dropped = 0

    def _jitter_s(self) -> float:
        # No draw without jitter, so that an ideal sensor's noise sequence is what it was before jitter existed.
        jitter_s = self.config.latency_jitter_s
        return abs(jitter_s * self.rng.standard_normal()) if jitter_s > 0.0 else 0.0

    def poll(self, now_s: float, measure: Callable[[float], Output | None]) -> list[tuple[float, float, Output]]:
        while self._next_sample_s <= now_s + _SCHEDULE_EPS_S:
            sample_s = self._next_sample_s
            # From the index, not by accumulation, so the schedule does not drift over long runs.
            self._sample_index += 1
            self._next_sample_s = self._start_s + self._sample_index * self.period_s
            self.samples_taken += 1
            # The draw happens even when forced so that a fault does not shift the noise of later samples.
            lost = self.rng.random() < self.config.dropout_probability
            if lost or self.forced_dropout:
                self.samples_dropped += 1
                continue
            output = measure(sample_s)
            if output is not None:
                delivery_s = max(sample_s + self.config.latency_s + self._jitter_s(), self._last_delivery_s)
                self._last_delivery_s = delivery_s
                heapq.heappush(self._pending, (delivery_s, next(self._order), sample_s, output))
        ready = []
        while self._pending and self._pending[0][0] <= now_s + _SCHEDULE_EPS_S:
            delivery_s, _, sample_s, output = heapq.heappop(self._pending)
            ready.append((sample_s, delivery_s, output))
        return ready


def stamp(header, sample_time_s: float, delivery_time_s: float, vehicle_id: str, sender: str,
          sequence: int) -> None:
    """Fill a coopdrive.v1 Header in place."""
    header.sample_time_s = sample_time_s
    header.sent_time_s = delivery_time_s
    header.vehicle_id = vehicle_id
    header.sender = sender
    header.sequence = sequence
