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

When the predecessor's requested acceleration u_p (iCLCM) is fresh, it replaces a_p. With drivelines alike,
a_p = G(s) u_p and a = G(s) u, so the same ideal a = a_p / (1 + h s) needs
      u_ff = z_u,   h z_u' + z_u = u_p                                                    (eq. C3)
which differentiates nothing (a measured a_p is noisy, and C1 amplifies it by tau/h), needs no lag estimate,
and leads the measured acceleration by the predecessor's dead time and lag.

The request arrives late by its age theta (V2V, the sender's and our own pipeline, and the wait of the 25 Hz
scene for the 50 Hz control: 0.11-0.12 s); a first-order lead makes up for most of it at platoon-wave
frequencies, e^(theta s) ~ 1 + theta s:
      u_ff = (1 + theta s) z_u = z_u + (theta / h) (u_p - z_u)                               (eq. C5)
The lead's theta must be the age at our control, not at the scene: the string gain is
H = (1 / (1 + h s)) (L + rho) / (1 + L) with rho = (1 + theta s) e^(-age s) (eq. SS2, string_stability.py), and
at the 0.2 Hz wave 1 / (1 + L) is almost imaginary, so a phase lag of rho raises |H| while its size hardly counts.

The PD acts through a first-order filter,
      tau_fb w' + w = kp e + kd e'                                                        (eq. C4)
because e' is the difference of two measured speeds and kd passes its noise straight to the command, where
every follower would feel it and hand it on; 0.2 s barely delays the 0.2 Hz platoon waves.
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
        self.filtered_intended_mps2 = 0.0
        self.filtered_feedback_mps2: float | None = None
        self.bump_offset_mps2 = 0.0

    def feedforward_mps2(self, f: FollowInput) -> float:
        if f.pred_intended_accel_mps2 is not None:
            lead = self.gains.request_lead_s / f.time_gap_s
            z_u = self.filtered_intended_mps2  # (eq. C3)
            return z_u + lead * (f.pred_intended_accel_mps2 - z_u)  # (eq. C5)
        ratio = self.engine_lag_s / f.time_gap_s
        return ratio * f.pred_accel_mps2 + (1.0 - ratio) * self.filtered_accel_mps2  # (eq. C1)

    def feedback_mps2(self, f: FollowInput) -> float:
        return self.gains.kp_1ps2 * f.spacing_error_m + self.gains.kd_1ps * f.spacing_error_rate_mps  # (eq. C2)

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Bumpless start from the applied command; an offset may only delay acceleration, never braking."""
        self.filtered_accel_mps2 = f.pred_accel_mps2
        self.filtered_intended_mps2 = f.pred_feedforward_accel_mps2
        self.filtered_feedback_mps2 = self.feedback_mps2(f)
        law = self.feedforward_mps2(f) + self.filtered_feedback_mps2
        self.bump_offset_mps2 = min(0.0, command_mps2 - law)

    def step(self, dt_s: float, f: FollowInput) -> float:
        # Exact discretisation of h z' + z = a_p for a_p held over the step. The request's filter follows the
        # measurement while no request arrives, so a request that appears continues from where C1 was.
        blend = 1.0 - math.exp(-dt_s / f.time_gap_s)
        self.filtered_accel_mps2 += blend * (f.pred_accel_mps2 - self.filtered_accel_mps2)
        self.filtered_intended_mps2 += blend * (f.pred_feedforward_accel_mps2 - self.filtered_intended_mps2)
        self.bump_offset_mps2 *= math.exp(-dt_s / self.gains.bump_time_constant_s)
        return self.feedforward_mps2(f) + self._filter_feedback(dt_s, self.feedback_mps2(f)) + self.bump_offset_mps2

    def _filter_feedback(self, dt_s: float, feedback_mps2: float) -> float:
        tau_s = self.gains.feedback_time_constant_s
        if self.filtered_feedback_mps2 is None or tau_s == 0.0:
            self.filtered_feedback_mps2 = feedback_mps2
        else:
            blend = 1.0 - math.exp(-dt_s / tau_s)
            self.filtered_feedback_mps2 += blend * (feedback_mps2 - self.filtered_feedback_mps2)  # (eq. C4)
        return self.filtered_feedback_mps2
