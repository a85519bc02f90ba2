"""Ploeg CACC, the reference cooperative law (Ploeg et al. 2011; Plexe / SUMO CC model).

    h du/dt = -u + kp e + kd de/dt + u_p,   e = gap - (r + h v),   de/dt = v_p - v - h a

u_p is the predecessor's requested acceleration (iCLCM) when fresh, as in Ploeg's paper, else its measured
acceleration as received over V2V. Integrated with explicit Euler.
"""

from __future__ import annotations

from ..profiles import PloegGains
from .types import FollowInput


class PloegCacc:
    def __init__(self, gains: PloegGains) -> None:
        self.gains = gains
        self.u_mps2 = 0.0

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Bumpless start: the filter state is the command being applied now (the situation f adds nothing)."""
        self.u_mps2 = command_mps2

    def step(self, dt_s: float, f: FollowInput) -> float:
        g = self.gains
        # (Ploeg CACC) du/dt = (1/h)[-u + kp e + kd de/dt + u_p]
        du = (-self.u_mps2 + g.kp_1ps2 * f.spacing_error_m + g.kd_1ps * f.spacing_error_rate_mps
              + f.pred_feedforward_accel_mps2)
        self.u_mps2 += dt_s * du / f.time_gap_s
        return self.u_mps2
