"""DRIVERTIVE (GCDC 2016) laws, kept as references.

Adaptive proportional speed law (eq. 4-5, Table II):
    u = K e,   K = K0 + Kv0 v  if e >= 0 (accelerate),   K = K1 + Kv1 v  if e < 0 (brake)
The paper's u is a pedal reference in [-1, 1]; here it is read as an acceleration request (K in 1/s),
with the same optional resistance feed-forward as the cruise PI. Being proportional, it keeps a
steady-state error under a disturbance it does not feed forward (as the paper notes).

Follow law (eq. 10), a dead-beat spacing law over one control period dt:
    a_h = (s_l - s_h - r) / (dt (th + dt/2)) + (v_l - v_h (1 + th/dt)) / (th + dt/2) + a_l dt / (2 th + dt)
"""

from __future__ import annotations

from ..profiles import VehicleProfile


class DrivertiveSpeed:
    def __init__(self, profile: VehicleProfile) -> None:
        self.profile = profile
        self.gains = profile.drivertive
        self.engaged = False

    def gain_1ps(self, speed_mps: float, error_mps: float) -> float:
        g = self.gains
        if error_mps >= 0:
            return g.k0_1ps + g.kv0_1pm * speed_mps  # (eq. 5) accelerating branch
        return g.k1_1ps + g.kv1_1pm * speed_mps  # (eq. 5) braking branch

    def reset(self, command_mps2: float, ego_speed_mps: float) -> None:
        """Static law: nothing to initialise."""

    def engage(self, command_mps2: float, ego_speed_mps: float) -> None:
        """Static law: nothing to initialise."""
        self.engaged = True

    def disengage(self) -> None:
        """Static law: nothing to release."""
        self.engaged = False

    def step(self, dt_s: float, ego_speed_mps: float, desired_speed_mps: float) -> float:
        error = desired_speed_mps - ego_speed_mps
        ff = self.profile.resistance_accel_mps2(ego_speed_mps) if self.profile.cruise.resistance_feedforward else 0.0
        return self.gain_1ps(ego_speed_mps, error) * error + ff  # (eq. 4)

    def track(self, dt_s: float, applied_mps2: float) -> None:
        """No integrator, nothing to wind up."""


def drivertive_follow_accel_mps2(
    gap_m: float,
    ego_speed_mps: float,
    pred_speed_mps: float,
    pred_accel_mps2: float,
    standstill_m: float,
    time_gap_s: float,
    dt_s: float,
) -> float:
    th, dt = time_gap_s, dt_s
    return (
        (gap_m - standstill_m) / (dt * (th + dt / 2))
        + (pred_speed_mps - ego_speed_mps * (1 + th / dt)) / (th + dt / 2)
        + pred_accel_mps2 * dt / (2 * th + dt)
    )  # (DRIVERTIVE eq. 10)
