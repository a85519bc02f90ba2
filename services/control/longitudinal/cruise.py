"""Cruise speed control: PI with resistance feed-forward (Heudiasyc eq. 3 at acceleration level).

Heudiasyc: T = m_e R_e (Kp e_v + Ki int e_v) + R_e F_a (eq. 3). Dividing by m_e R_e gives an acceleration
request; we add rolling resistance to the aerodynamic term (eq. 2) and track a reference model instead of the
raw set-point, so a set-point step gives no overshoot (the PI zero would otherwise cause one):
    a_ref' = clip_jerk( clip( (v_des - v_ref) / T_ref, -a_dec, a_acc ) - a_ref ),  v_ref' = a_ref  (eq. S1)
    u = a_ref + tau a_ref' + Kp (v_ref - v) + I + F_res(v) / m                                     (eq. S2)
    I' = Ki (v_ref - v) + (u_applied - u) / T_t          (back-calculation anti-windup)            (eq. S3)
tau a_ref' inverts the driveline lag, so the vehicle follows the model and the PI only fixes model error.

While another law commands (min-select), cruise is disengaged and offers the governor value
    u_gov = clip((v_des - v) / T_gov, -a_max_decel, a_max_accel) + F_res / m                     (eq. S4)
with the comfort limits and a short T_gov: a speed limiter that binds only near the set speed. Capping
following at the reference model's gentler acceleration would let a follower brake harder than it may
accelerate, so it would fall behind a predecessor whose speed oscillates. When it wins, `engage` starts the
model at the measured speed with the applied command (bumpless); the shaper's jerk limit smooths the step into
the governor value.
"""

from __future__ import annotations

from ..profiles import VehicleProfile


class CruisePi:
    def __init__(self, profile: VehicleProfile) -> None:
        self.profile = profile
        self.gains = profile.cruise
        self.speed_ref_mps = 0.0
        self.accel_ref_mps2 = 0.0
        self.integral_mps2 = 0.0
        self.last_output_mps2 = 0.0
        self._jerk_ref_mps3 = 0.0
        self.engaged = False

    def _resistance_mps2(self, speed_mps: float) -> float:
        return self.profile.resistance_accel_mps2(speed_mps) if self.gains.resistance_feedforward else 0.0

    def _caps_mps2(self) -> tuple[float, float]:
        g, lim = self.gains, self.profile.limits
        return min(g.reference_accel_mps2, lim.max_accel_mps2), min(g.reference_decel_mps2, lim.max_decel_mps2)

    def _wanted_mps2(self, speed_from_mps: float, desired_speed_mps: float) -> float:
        accel_cap, decel_cap = self._caps_mps2()
        wanted = (desired_speed_mps - speed_from_mps) / self.gains.reference_time_constant_s
        return min(max(wanted, -decel_cap), accel_cap)

    def _governor_mps2(self, ego_speed_mps: float, desired_speed_mps: float) -> float:
        lim = self.profile.limits
        wanted = (desired_speed_mps - ego_speed_mps) / self.gains.governor_time_constant_s
        return min(max(wanted, -lim.max_decel_mps2), lim.max_accel_mps2) + self._resistance_mps2(ego_speed_mps)  # (eq. S4)

    def disengage(self) -> None:
        self.engaged = False

    def engage(self, command_mps2: float, ego_speed_mps: float) -> None:
        self.reset(command_mps2, ego_speed_mps)
        self.engaged = True

    def reset(self, command_mps2: float, ego_speed_mps: float) -> None:
        """Bumpless: the model starts at the current speed with the net acceleration of the applied command,
        within the model's own limits: after emergency braking the model must not go on braking that hard."""
        accel_cap, decel_cap = self._caps_mps2()
        self.speed_ref_mps = ego_speed_mps
        self.accel_ref_mps2 = min(max(command_mps2 - self._resistance_mps2(ego_speed_mps), -decel_cap), accel_cap)
        self.integral_mps2 = 0.0
        self._jerk_ref_mps3 = 0.0
        self.last_output_mps2 = command_mps2

    def step(self, dt_s: float, ego_speed_mps: float, desired_speed_mps: float) -> float:
        g = self.gains
        if not self.engaged:
            self.last_output_mps2 = self._governor_mps2(ego_speed_mps, desired_speed_mps)
            return self.last_output_mps2
        wanted = self._wanted_mps2(self.speed_ref_mps, desired_speed_mps)
        max_step = g.reference_jerk_mps3 * dt_s
        delta = min(max(wanted - self.accel_ref_mps2, -max_step), max_step)  # (eq. S1)
        self._jerk_ref_mps3 = delta / dt_s
        self.accel_ref_mps2 += delta
        self.speed_ref_mps += self.accel_ref_mps2 * dt_s
        if self.speed_ref_mps < 0.0:
            # The reference stops at standstill; it does not reverse.
            self.speed_ref_mps, self.accel_ref_mps2 = 0.0, max(self.accel_ref_mps2, 0.0)
        error = self.speed_ref_mps - ego_speed_mps
        self.integral_mps2 += g.ki_1ps2 * error * dt_s
        self.last_output_mps2 = (
            self.accel_ref_mps2
            + self.profile.engine_lag_s * self._jerk_ref_mps3
            + g.kp_1ps * error
            + self.integral_mps2
            + self._resistance_mps2(ego_speed_mps)
        )  # (eq. S2)
        return self.last_output_mps2

    def track(self, dt_s: float, applied_mps2: float) -> None:
        """Anti-windup (eq. S3): pull the integrator towards the command that was actually applied."""
        if not self.engaged:
            return
        self.integral_mps2 += dt_s * (applied_mps2 - self.last_output_mps2) / self.gains.tracking_time_constant_s
