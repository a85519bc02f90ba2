"""WheelScaleEstimator: the ratio of true speed to wheel-speed-sensor speed, estimated against GNSS speed.

A wheel-speed sensor counts wheel revolutions; the speed it reports assumes a nominal rolling radius, which
tyre wear, pressure and temperature change by a percent or two. The scale s (true = s x reported) is modelled as
a slowly varying random walk and estimated by a scalar Kalman filter: each GNSS fix moving fast enough gives a
measurement v_gnss = s * v_wheels + noise, with v_wheels the reported speed at the fix's time, interpolated between
the wheel samples either side of it. A fix waits for the wheel sample after its time: the wheels' frames may reach
the service later than the fix (their latency, a log's clock), and the speed before the fix's time alone is the
speed of up to a sample period earlier, at 20 m/s2 of braking 0.2 m/s off. Measurements far from the prediction
(wheel slip, a GNSS outlier) are gated out and counted, so one bad fix cannot pull the scale.
"""

from __future__ import annotations

import bisect
import math
from collections import Counter, deque

# Below this speed a percent of scale is lost in the GNSS speed noise.
MIN_SPEED_MPS = 3.0
# How far apart the wheel-speed samples either side of a fix may be (wheel speeds arrive at 50-100 Hz).
MAX_PAIRING_GAP_S = 0.05
# Fixes waiting for the wheel sample after their time; older ones are dropped (the wheels have stopped reporting).
MAX_WAITING_FIXES = 20
WHEEL_HISTORY = 200
# Scale drift: tyres warm up and lose pressure over minutes (one sigma per square-root second).
SCALE_DRIFT_PER_SQRT_S = 1e-4
INITIAL_SCALE_STD = 0.02
# GNSS Doppler speed noise (one sigma); a few cm/s for an automotive receiver, more for a phone-grade one.
GNSS_SPEED_STD_MPS = 0.1
# Innovation gate in sigmas.
GATE_SIGMAS = 4.0
# A scale outside these bounds is a fault, not a tyre.
SCALE_BOUNDS = (0.8, 1.2)


class WheelScaleEstimator:
    def __init__(self, gnss_speed_std_mps: float = GNSS_SPEED_STD_MPS) -> None:
        self.scale = 1.0
        self.variance = INITIAL_SCALE_STD**2
        self.gnss_speed_std_mps = gnss_speed_std_mps
        self.counts: Counter[str] = Counter()
        self._time_s: float | None = None
        self._wheel_times_s: deque[float] = deque(maxlen=WHEEL_HISTORY)
        self._wheel_speeds_mps: deque[float] = deque(maxlen=WHEEL_HISTORY)
        self._waiting: deque[tuple[float, float]] = deque()

    @property
    def std(self) -> float:
        return math.sqrt(self.variance)

    def on_wheel_speed(self, time_s: float, reported_speed_mps: float) -> None:
        """The wheels' speed as reported (before scaling); samples must come in time order."""
        if self._wheel_times_s and time_s < self._wheel_times_s[-1]:
            return
        self._wheel_times_s.append(time_s)
        self._wheel_speeds_mps.append(reported_speed_mps)
        while self._waiting and self._waiting[0][0] <= time_s:
            self._update(*self._waiting.popleft())

    def on_gnss_speed(self, time_s: float, gnss_speed_mps: float) -> None:
        """A fix's speed over ground: updates the scale once the wheels have reported past the fix's time."""
        if self._wheel_times_s and time_s <= self._wheel_times_s[-1]:
            self._update(time_s, gnss_speed_mps)
            return
        if len(self._waiting) == MAX_WAITING_FIXES:
            self._waiting.popleft()
            self.counts["wheel_scale_unused"] += 1
        self._waiting.append((time_s, gnss_speed_mps))

    def _update(self, time_s: float, gnss_speed_mps: float) -> None:
        """One fix's speed against the wheels' at its time; counted as unused, gated or an update."""
        reported = self._reported_at(time_s)
        if reported is None or abs(reported) < MIN_SPEED_MPS or gnss_speed_mps < MIN_SPEED_MPS:
            self.counts["wheel_scale_unused"] += 1
            return
        if self._time_s is not None and time_s > self._time_s:
            self.variance += SCALE_DRIFT_PER_SQRT_S**2 * (time_s - self._time_s)
        self._time_s = time_s if self._time_s is None else max(self._time_s, time_s)
        v = abs(reported)
        innovation = gnss_speed_mps - self.scale * v
        innovation_variance = v * v * self.variance + self.gnss_speed_std_mps**2
        if innovation * innovation > GATE_SIGMAS**2 * innovation_variance:
            self.counts["wheel_scale_gated"] += 1
            return
        gain = v * self.variance / innovation_variance
        self.scale = min(max(self.scale + gain * innovation, SCALE_BOUNDS[0]), SCALE_BOUNDS[1])
        self.variance *= 1.0 - gain * v
        self.counts["wheel_scale_updates"] += 1

    def _reported_at(self, time_s: float) -> float | None:
        """The reported speed at time_s, interpolated between the samples either side; None without both, or
        with them too far apart."""
        times = self._wheel_times_s
        after = bisect.bisect_left(times, time_s)
        if after == len(times):
            return None
        if times[after] == time_s:
            return self._wheel_speeds_mps[after]
        if after == 0 or times[after] - times[after - 1] > MAX_PAIRING_GAP_S:
            return None
        before_s, after_s = times[after - 1], times[after]
        before_mps, after_mps = self._wheel_speeds_mps[after - 1], self._wheel_speeds_mps[after]
        return before_mps + (time_s - before_s) / (after_s - before_s) * (after_mps - before_mps)
