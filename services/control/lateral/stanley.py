"""Stanley path tracking (Snider 2009, sec. 2.3; Heudiasyc ref. [17]) with curvature feed-forward.

Cross-track error at the front axle, y_f = y + L sin(theta); reference heading theta_d = atan(y_d' / v):
    delta = (theta_d - theta) + atan( k (y_d - y_f) / (k_s + v) ) + atan(L kappa)          (eq. St1)
"""

from __future__ import annotations

import math

from ..profiles import LateralGains
from .types import PathState


class Stanley:
    def __init__(self, gains: LateralGains, wheelbase_m: float) -> None:
        self.gains = gains
        self.wheelbase_m = wheelbase_m

    def steering_rad(self, p: PathState) -> float:
        g, wb = self.gains, self.wheelbase_m
        v = max(p.speed_mps, 0.0)
        front_offset = p.lateral_offset_m + wb * math.sin(p.heading_error_rad)
        heading_ref = math.atan2(p.reference_rate_mps, max(v, g.min_speed_mps))
        cross = math.atan2(g.stanley_gain * (p.reference_offset_m - front_offset), g.stanley_softening_mps + v)
        return (heading_ref - p.heading_error_rad) + cross + math.atan(wb * p.curvature_1pm)  # (eq. St1)
