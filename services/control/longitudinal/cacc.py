"""Our CACC: predecessor acceleration feed-forward that compensates our own driveline lag.

Derivation (constant time gap, driveline tau a' + a = u):
  zero spacing error needs e'' = 0, i.e. h a' + a = a_p, so the ideal acceleration is a = a_p / (1 + h s);
  with the lag, the input that produces it is
      u_ff = (1 + tau s) / (1 + h s) a_p = (tau/h) a_p + (1 - tau/h) z,   h z' + z = a_p     (eq. C1)
  and a PD on the spacing error corrects what the feed-forward misses:
      u = u_ff + kp e + kd e',   e = gap - (r + h v),   e' = v_p - v - h a                 (eq. C2)
Without delays the speed transfer is exactly 1 / (1 + h s) for any lag, as Ploeg's with the predecessor's
*command*; Ploeg fed with the predecessor's *measured* acceleration keeps an uncompensated lag, and the large
kd keeps ours string stable with 0.1-0.25 s of communication plus actuation delay (string_stability.py).
"""

from __future__ import annotations

import math

from ..profiles import CaccGains
from .types import FollowInput


class LagCompensatedCacc:
    def __init__(self, gains: CaccGains, engine_lag_s: float) -> None:
        self.gains = gains
        self.engine_lag_s = engine_lag_s
        self.filtered_accel_mps2 = 0.0
        self.bump_offset_mps2 = 0.0

    def feedforward_mps2(self, pred_accel_mps2: float, time_gap_s: float) -> float:
        ratio = self.engine_lag_s / time_gap_s
        return ratio * pred_accel_mps2 + (1.0 - ratio) * self.filtered_accel_mps2  # (eq. C1)

    def feedback_mps2(self, f: FollowInput) -> float:
        return self.gains.kp_1ps2 * f.spacing_error_m + self.gains.kd_1ps * f.spacing_error_rate_mps  # (eq. C2)

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Bumpless start from the applied command; an offset may only delay acceleration, never braking."""
        self.filtered_accel_mps2 = f.pred_accel_mps2
        law = self.feedforward_mps2(f.pred_accel_mps2, f.time_gap_s) + self.feedback_mps2(f)
        self.bump_offset_mps2 = min(0.0, command_mps2 - law)

    def step(self, dt_s: float, f: FollowInput) -> float:
        # Exact discretisation of h z' + z = a_p for a_p held over the step.
        self.filtered_accel_mps2 += (1.0 - math.exp(-dt_s / f.time_gap_s)) * (
            f.pred_accel_mps2 - self.filtered_accel_mps2
        )
        self.bump_offset_mps2 *= math.exp(-dt_s / self.gains.bump_time_constant_s)
        return self.feedforward_mps2(f.pred_accel_mps2, f.time_gap_s) + self.feedback_mps2(f) + self.bump_offset_mps2
