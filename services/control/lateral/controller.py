"""Lateral controller: reference offset management (smooth lane change), a selectable law, and limits.

Input offsets are relative to the centre line of the *target* lane. When the planner switches the target lane,
that offset jumps by about a lane width (Heudiasyc's reference switch); when it asks for another offset in the
lane (emergency corridor) the desired offset jumps. Either jump starts a quintic reference transition from
where the vehicle is to the desired offset, so the law never sees a step.

Output limits, in order: |delta| <= atan(L a_lat_max / v^2) (lateral acceleration v^2 tan(delta) / L), the
road-wheel angle limit, then the steering rate limit. Curvature is tan(delta) / L of the limited angle.
"""

from __future__ import annotations

import math

from ..profiles import VehicleProfile
from ..step_period import step_period_s
from .lane_change import QuinticTransition
from .pd import HeudiasycPd
from .pure_pursuit import PurePursuit
from .stanley import Stanley
from .types import LateralCommand, LateralLaw, LateralMode, PathState, SteeringLaw

# A change of the offset to the target lane centre larger than this between two steps is a reference switch.
REFERENCE_JUMP_M = 1.0


class LateralController:
    def __init__(self, profile: VehicleProfile, law: LateralLaw = LateralLaw.HEUDIASYC_PD) -> None:
        self.profile = profile
        self.law_kind = law
        wb = profile.wheelbase_m
        gains = profile.lateral
        self.law: SteeringLaw = {
            LateralLaw.HEUDIASYC_PD: HeudiasycPd,
            LateralLaw.STANLEY: Stanley,
            LateralLaw.PURE_PURSUIT: PurePursuit,
        }[law](gains, wb)
        self.transition: QuinticTransition | None = None
        self.rejected_inputs = 0
        self.steering_rad = 0.0
        self._last_time_s: float | None = None
        self._last_offset_m: float | None = None
        self._last_desired_m: float | None = None

    def reset(self, steering_rad: float = 0.0) -> None:
        self.steering_rad = steering_rad
        self.transition = None
        self._last_time_s = self._last_offset_m = self._last_desired_m = None

    def _maybe_start_transition(self, time_s: float, p: PathState, desired_m: float, duration_s: float) -> None:
        jumped = self._last_offset_m is not None and abs(p.lateral_offset_m - self._last_offset_m) > REFERENCE_JUMP_M
        retargeted = self._last_desired_m is not None and abs(desired_m - self._last_desired_m) > 1e-6
        first = self._last_offset_m is None and abs(p.lateral_offset_m - desired_m) > REFERENCE_JUMP_M
        if jumped or retargeted or first:
            start_rate = p.speed_mps * math.sin(p.heading_error_rad)  # (eq. 7) current lateral speed
            self.transition = QuinticTransition(time_s, duration_s, p.lateral_offset_m, desired_m, start_rate)

    def step(
        self,
        time_s: float,
        speed_mps: float,
        lateral_offset_m: float,
        heading_error_rad: float,
        curvature_1pm: float = 0.0,
        desired_offset_m: float = 0.0,
        lane_change_duration_s: float | None = None,
    ) -> LateralCommand:
        """One period. Offsets in m positive left of the target lane centre, angles in rad, curvature in 1/m."""
        for name, value in (("time_s", time_s), ("speed_mps", speed_mps), ("lateral_offset_m", lateral_offset_m),
                            ("heading_error_rad", heading_error_rad), ("curvature_1pm", curvature_1pm),
                            ("desired_offset_m", desired_offset_m)):
            if not math.isfinite(value):
                self.rejected_inputs += 1
                raise ValueError(f"lateral controller: {name} is not finite ({value})")
        dt, _ = step_period_s(self._last_time_s, time_s)
        duration = lane_change_duration_s or self.profile.lateral.lane_change_duration_s
        measured = PathState(speed_mps, lateral_offset_m, heading_error_rad, curvature_1pm)
        self._maybe_start_transition(time_s, measured, desired_offset_m, duration)
        self._last_time_s, self._last_offset_m, self._last_desired_m = time_s, lateral_offset_m, desired_offset_m

        if self.transition is not None and self.transition.done(time_s):
            self.transition = None
        transition = self.transition
        if transition is not None:
            y_d, dy_d, ddy_d = transition.sample(time_s)

            def preview(ahead_s: float) -> float:
                return transition.sample(time_s + ahead_s)[0]
        else:
            y_d, dy_d, ddy_d = desired_offset_m, 0.0, 0.0

            def preview(ahead_s: float) -> float:
                return desired_offset_m
        p = PathState(speed_mps, lateral_offset_m, heading_error_rad, curvature_1pm, y_d, dy_d, ddy_d, preview)
        wanted = self.law.steering_rad(p)

        wb, lim = self.profile.wheelbase_m, self.profile.steering
        v = max(speed_mps, self.profile.lateral.min_speed_mps)
        max_angle = min(lim.max_angle_rad, math.atan(wb * lim.max_lateral_accel_mps2 / v**2))
        wanted = min(max(wanted, -max_angle), max_angle)
        step = lim.max_rate_radps * dt
        self.steering_rad = min(max(wanted, self.steering_rad - step), self.steering_rad + step)
        return LateralCommand(
            steering_angle_rad=self.steering_rad,
            curvature_1pm=math.tan(self.steering_rad) / wb,
            mode=LateralMode.LATERAL_MODE_LANE_CHANGE if self.transition is not None else LateralMode.LATERAL_MODE_LANE_KEEPING,
            lateral_error_m=p.lateral_error_m,
            heading_error_rad=heading_error_rad,
            reference_offset_m=y_d,
            lane_change_active=self.transition is not None,
        )
