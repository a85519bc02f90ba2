"""Radar-only following laws: the Rajamani ACC reference and ours.

Rajamani (Vehicle Dynamics and Control, constant time gap ACC; SUMO CC model):
    u = -(1/h) [ (v - v_p) + lambda (-gap + h v + r) ]                                   (eq. R1)
Ours adds a spacing-rate term through our own acceleration and stiffer gains (string stable for
h >= 1.2 s with lag <= 0.5 s and 50 ms dead time, see string_stability.py):
    u = kv (v_p - v) + ke (gap - r - h v) - ka h a                                        (eq. A1)
Both are static, so switching to them needs no state: the jerk limit smooths the transfer.
"""

from __future__ import annotations

from ..profiles import AccGains, RajamaniGains
from .types import FollowInput


class RajamaniAcc:
    def __init__(self, gains: RajamaniGains) -> None:
        self.gains = gains

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Static law: nothing to initialise."""

    def step(self, dt_s: float, f: FollowInput) -> float:
        h = f.time_gap_s
        # (eq. R1) Rajamani ACC
        return -((f.ego_speed_mps - f.pred_speed_mps) + self.gains.lambda_1ps * (-f.gap_m + h * f.ego_speed_mps + f.standstill_m)) / h


class RadarAcc:
    def __init__(self, gains: AccGains) -> None:
        self.gains = gains

    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Static law: nothing to initialise."""

    def step(self, dt_s: float, f: FollowInput) -> float:
        g = self.gains
        # (eq. A1) our ACC
        return (
            g.kv_1ps * (f.pred_speed_mps - f.ego_speed_mps)
            + g.ke_1ps2 * f.spacing_error_m
            - g.ka * f.time_gap_s * f.ego_accel_mps2
        )
