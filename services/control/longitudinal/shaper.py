"""Output shaping: comfort acceleration limits and a jerk limit; the emergency path has its own wider limits.

    u_k = clip( clip(u_req, -a_dec, a_acc), u_{k-1} - J dt, u_{k-1} + J dt )              (eq. L1)
A brake beyond comfort (u_{k-1} < -a_dec, left by the emergency path) is released at the emergency jerk J_e as far
as -a_dec, and at J from there:
    upper bound = min( u_{k-1} + J_e dt, max(-a_dec, u_{k-1} + J dt) )                   (eq. L1b)
ISO 15622 bounds how fast a brake may come on, not how fast it may go; held at the comfort jerk, a 0.3 s emergency
brake for a phantom went on braking for 1.5 s after it (emergency seed 6).
The applied u_k is fed back to the laws (anti-windup and bumpless transfer), never the raw request.
"""

from __future__ import annotations

from ..profiles import LimitGains


class CommandShaper:
    def __init__(self, limits: LimitGains) -> None:
        self.limits = limits
        self.last_mps2 = 0.0

    def reset(self, command_mps2: float) -> None:
        self.last_mps2 = command_mps2

    def step(self, dt_s: float, request_mps2: float, emergency: bool = False) -> float:
        lim = self.limits
        if emergency:
            low, jerk = -lim.emergency_decel_mps2, lim.emergency_jerk_mps3
        else:
            low, jerk = -lim.max_decel_mps2, lim.max_jerk_mps3
        wanted = min(max(request_mps2, low), lim.max_accel_mps2)
        last = self.last_mps2
        upper = last + jerk * dt_s
        if last < -lim.max_decel_mps2:
            upper = min(last + lim.emergency_jerk_mps3 * dt_s, max(-lim.max_decel_mps2, upper))  # (eq. L1b)
        self.last_mps2 = min(max(wanted, last - jerk * dt_s), upper)  # (eq. L1)
        return self.last_mps2
