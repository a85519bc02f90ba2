"""dCACC (Ploeg et al. 2015, graceful degradation): our CACC fed with an estimated predecessor acceleration.

The predecessor speed is v_p = v + range rate; its acceleration is the least-squares slope over the last
window of samples
    a_p ~= sum (t_i - t_mean)(v_p,i - v_mean) / sum (t_i - t_mean)^2                     (eq. D1)
which lags by about half the window; the caller raises the time gap to pay for that lag.
"""

from __future__ import annotations

from collections import deque
from dataclasses import replace

from ..profiles import CaccGains, DcaccGains
from .cacc import LagCompensatedCacc
from .types import FollowInput


class RangeRateAccelEstimator:
    def __init__(self, gains: DcaccGains) -> None:
        self.gains = gains
        self._samples: deque[tuple[float, float]] = deque()
        # Asked for several times per control step (readiness, command, diagnostics): fit once per sample.
        self._estimate_mps2: float | None = None
        self._estimate_stale = False

    def observe(self, time_s: float, ego_speed_mps: float, range_rate_mps: float) -> None:
        if self._samples and time_s <= self._samples[-1][0]:
            return
        self._samples.append((time_s, ego_speed_mps + range_rate_mps))
        while self._samples and time_s - self._samples[0][0] > self.gains.estimator_window_s:
            self._samples.popleft()
        self._estimate_stale = True

    def estimate_mps2(self) -> float | None:
        """Predecessor acceleration, or None until the window holds enough samples."""
        if self._estimate_stale:
            self._estimate_mps2 = self._fit()
            self._estimate_stale = False
        return self._estimate_mps2

    def _fit(self) -> float | None:
        n = len(self._samples)
        if n < self.gains.estimator_min_samples:
            return None
        t_mean = sum(t for t, _ in self._samples) / n
        v_mean = sum(v for _, v in self._samples) / n
        num = sum((t - t_mean) * (v - v_mean) for t, v in self._samples)
        den = sum((t - t_mean) ** 2 for t, _ in self._samples)
        return num / den if den > 0 else None  # (eq. D1)


class Dcacc:
    def __init__(self, cacc_gains: CaccGains, dcacc_gains: DcaccGains, engine_lag_s: float) -> None:
        self.estimator = RangeRateAccelEstimator(dcacc_gains)
        self.law = LagCompensatedCacc(cacc_gains, engine_lag_s)

    def observe(self, time_s: float, ego_speed_mps: float, range_rate_mps: float) -> None:
        self.estimator.observe(time_s, ego_speed_mps, range_rate_mps)

    def ready(self) -> bool:
        return self.estimator.estimate_mps2() is not None

    def with_estimate(self, f: FollowInput) -> FollowInput:
        est = self.estimator.estimate_mps2()
        return replace(f, pred_accel_mps2=0.0 if est is None else est, pred_intended_accel_mps2=None)

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        self.law.reset(command_mps2, self.with_estimate(f))

    def step(self, dt_s: float, f: FollowInput) -> float:
        return self.law.step(dt_s, self.with_estimate(f))
