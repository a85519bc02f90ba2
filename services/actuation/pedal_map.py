"""PedalMap: acceleration request -> throttle and brake (DRIVERTIVE Sect. II.A.2-3 and II.B.2).

A unique reference r in [-1, 1] keeps throttle and brake mutually exclusive: r > 0 acts on the throttle only,
r < 0 on the brake only. r is the acceleration request scaled by what full throttle or full brake achieves.
"""

from dataclasses import dataclass

from coopdrive.services.actuation.config import PedalProfile

R_MIN = -1.0
R_MAX = 1.0


@dataclass(frozen=True)
class PedalCommand:
    accel_request_mps2: float
    # DRIVERTIVE's unique control reference r(k).
    reference: float
    throttle_ratio: float
    brake_ratio: float
    throttle_voltage_v: float
    throttle_half_voltage_v: float
    # Calibrated pedal pressure of DRIVERTIVE Fig. 2 (unit not given in the paper).
    brake_pedal_pressure: float
    deceleration_request_mps2: float


def _clamp(value: float, low: float, high: float) -> float:
    return max(low, min(high, value))


class PedalMap:
    def __init__(self, profile: PedalProfile):
        self.profile = profile

    def reference(self, accel_request_mps2: float) -> float:
        if accel_request_mps2 >= 0.0:
            r = accel_request_mps2 / self.profile.accel_at_full_throttle_mps2
        else:
            r = accel_request_mps2 / self.profile.decel_at_full_brake_mps2
        return _clamp(r, R_MIN, R_MAX)

    def map(self, accel_request_mps2: float) -> PedalCommand:
        r = self.reference(accel_request_mps2)
        throttle = max(r, 0.0)
        brake = max(-r, 0.0)
        p = self.profile
        return PedalCommand(
            accel_request_mps2=accel_request_mps2,
            reference=r,
            throttle_ratio=throttle,
            brake_ratio=brake,
            throttle_voltage_v=p.throttle_offset_v + p.throttle_gain_v * throttle,  # (eq. 1) DRIVERTIVE
            throttle_half_voltage_v=(p.throttle_offset_v + p.throttle_gain_v * throttle) / 2.0,  # (eq. 2)
            brake_pedal_pressure=-p.brake_pressure_gain * min(r, 0.0),  # (eq. 3) DRIVERTIVE
            deceleration_request_mps2=brake * p.decel_at_full_brake_mps2 if p.uses_deceleration_request else 0.0,
        )
