"""Lane change as a smooth reference transition (Heudiasyc switch the reference lane; we smooth the switch).

Quintic y_d(t) from (y0, y0', 0) to (y1, 0, 0) over the duration T, tau = t / T, D = y1 - y0:
    y_d = y0 + y0' t + c3 t^3 + c4 t^4 + c5 t^5, coefficients solving the six boundary conditions     (eq. Q1)
With y0' = 0 this is y0 + D (10 tau^3 - 15 tau^4 + 6 tau^5), peak |y_d''| = 5.77 |D| / T^2.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class QuinticTransition:
    start_time_s: float
    duration_s: float
    start_offset_m: float
    end_offset_m: float
    start_rate_mps: float = 0.0

    def _coeffs(self) -> tuple[float, float, float]:
        t = self.duration_s
        d = self.end_offset_m - self.start_offset_m - self.start_rate_mps * t
        # Remaining boundary conditions y(T) = y1, y'(T) = 0, y''(T) = 0 for the c3, c4, c5 terms (eq. Q1).
        r = -self.start_rate_mps
        c3 = (10 * d - 4 * r * t) / t**3
        c4 = (-15 * d + 7 * r * t) / t**4
        c5 = (6 * d - 3 * r * t) / t**5
        return c3, c4, c5

    def done(self, time_s: float) -> bool:
        return time_s - self.start_time_s >= self.duration_s

    def sample(self, time_s: float) -> tuple[float, float, float]:
        """(y_d [m], y_d' [m/s], y_d'' [m/s2]) at time_s."""
        t = min(max(time_s - self.start_time_s, 0.0), self.duration_s)
        if t >= self.duration_s:
            return self.end_offset_m, 0.0, 0.0
        c3, c4, c5 = self._coeffs()
        y = self.start_offset_m + self.start_rate_mps * t + c3 * t**3 + c4 * t**4 + c5 * t**5
        dy = self.start_rate_mps + 3 * c3 * t**2 + 4 * c4 * t**3 + 5 * c5 * t**4
        ddy = 6 * c3 * t + 12 * c4 * t**2 + 20 * c5 * t**3
        return y, dy, ddy
