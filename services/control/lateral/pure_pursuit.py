"""Pure pursuit (Snider 2009, sec. 2.2) on the lane frame.

Look-ahead l_d = max(l_min, T_la v). The goal point lies l_d ahead on the reference, whose offset there is
y_d(t + l_d / v) from the lane change profile (linearised y_d + y_d' l_d / v without one), bent by the lane
curvature (kappa l_d^2 / 2). Its bearing in the vehicle frame is
    alpha = atan2(y_goal - y, l_d) - theta,     delta = atan( 2 L sin(alpha) / l_d )         (eq. PP1)
"""

from __future__ import annotations

import math

from ..profiles import LateralGains
from .types import PathState


class PurePursuit:
    def __init__(self, gains: LateralGains, wheelbase_m: float) -> None:
        self.gains = gains
        self.wheelbase_m = wheelbase_m

    def lookahead_m(self, speed_mps: float) -> float:
        return max(self.gains.pure_pursuit_min_lookahead_m, self.gains.pure_pursuit_lookahead_time_s * speed_mps)

    def steering_rad(self, p: PathState) -> float:
        ld = self.lookahead_m(p.speed_mps)
        v = max(p.speed_mps, self.gains.min_speed_mps)
        if p.reference_preview is not None:
            ahead = p.reference_preview(ld / v)
        else:
            ahead = p.reference_offset_m + p.reference_rate_mps * ld / v
        goal = ahead + 0.5 * p.curvature_1pm * ld**2
        alpha = math.atan2(goal - p.lateral_offset_m, ld) - p.heading_error_rad
        return math.atan(2.0 * self.wheelbase_m * math.sin(alpha) / ld)  # (eq. PP1)
