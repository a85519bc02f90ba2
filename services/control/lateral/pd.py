"""Heudiasyc lateral PD on the kinematic bicycle (Xu et al. 2018, eq. 7-10) with curvature feed-forward.

With small angles y' = v theta and theta' = v delta / L (eq. 7), so y'' = v^2 delta / L (eq. 8): a double integrator,
    delta = L / v^2 ( alpha1 (y_d - y) + alpha2 (y_d' - v theta) + y_d'' )                 (eq. 9)
which for a straight reference is eq. 10, delta = L/v^2 (alpha1 e_l + alpha2 v e_theta). On a curve the
lane heading turns at v kappa, held by the Ackermann feed-forward atan(L kappa) added to eq. 9.
alpha1 = wn^2, alpha2 = 2 wn gives the critically damped error e'' + alpha2 e' + alpha1 e = 0.
v is floored at min_speed_mps: eq. 10 is singular at standstill.
"""

from __future__ import annotations

import math

from ..profiles import LateralGains
from .types import PathState


class HeudiasycPd:
    def __init__(self, gains: LateralGains, wheelbase_m: float) -> None:
        self.gains = gains
        self.wheelbase_m = wheelbase_m

    def steering_rad(self, p: PathState) -> float:
        g, wb = self.gains, self.wheelbase_m
        v = max(p.speed_mps, g.min_speed_mps)
        lateral_rate = p.speed_mps * p.heading_error_rad  # (eq. 7)
        accel = (
            g.alpha1_1ps2 * p.lateral_error_m
            + g.alpha2_1ps * (p.reference_rate_mps - lateral_rate)
            + p.reference_accel_mps2
        )
        return wb / v**2 * accel + math.atan(wb * p.curvature_1pm)  # (eq. 9) + curvature feed-forward
