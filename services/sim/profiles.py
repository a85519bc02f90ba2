"""Vehicle profiles: geometry, actuator dynamics and limits, with units in the field names."""
from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field

STANDARD_GRAVITY_MPS2 = 9.80665
AIR_DENSITY_KGPM3 = 1.2


def rolling_resistance_mps2(rolling_coefficient: float) -> float:
    """Rolling resistance as a deceleration: c_r g."""
    return rolling_coefficient * STANDARD_GRAVITY_MPS2


def drag_1pm(drag_area_m2: float, mass_kg: float) -> float:
    """Aerodynamic drag as a deceleration per speed squared: rho c_d A / (2 m)."""
    return 0.5 * AIR_DENSITY_KGPM3 * drag_area_m2 / mass_kg


class ProfileName(enum.Enum):
    PASSENGER_CAR = "passenger_car"
    TRUCK = "truck"


class VehicleProfile(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    length_m: float = Field(gt=0)
    width_m: float = Field(gt=0)
    height_m: float = Field(gt=0)
    wheelbase_m: float = Field(gt=0)
    track_width_m: float = Field(gt=0)
    rear_overhang_m: float = Field(ge=0)
    # First-order lag of the powertrain and brakes: a_k = alpha u_k + (1 - alpha) a_{k-1}.
    accel_time_constant_s: float = Field(ge=0)
    accel_dead_time_s: float = Field(ge=0)
    # Acceleration at full throttle and deceleration at full brake: the same scale as actuation's PedalProfile
    # (accel_at_full_throttle_mps2, decel_at_full_brake_mps2), so its pedal map inverts ours.
    max_accel_mps2: float = Field(gt=0)
    max_decel_mps2: float = Field(gt=0)
    max_jerk_mps3: float = Field(gt=0)
    steer_time_constant_s: float = Field(ge=0)
    steer_dead_time_s: float = Field(ge=0)
    max_steer_rad: float = Field(gt=0)
    max_steer_rate_radps: float = Field(gt=0)
    max_speed_mps: float = Field(gt=0)
    # Brake line pressure at full braking, reported on the CAN bus.
    max_brake_pressure_bar: float = Field(gt=0)
    # Driving resistance the powertrain must overcome: a_res = rolling + drag v^2 (0 = an ideal actuator).
    rolling_resistance_mps2: float = Field(default=0.0, ge=0)
    drag_1pm: float = Field(default=0.0, ge=0)


# DRIVERTIVE's car reached 1.6-1.8 m/s2 at full throttle and GCDC capped requests at 2 m/s2.
PASSENGER_CAR = VehicleProfile(
    length_m=4.5, width_m=1.8, height_m=1.5, wheelbase_m=2.7, track_width_m=1.55, rear_overhang_m=0.9,
    accel_time_constant_s=0.5, accel_dead_time_s=0.1, max_accel_mps2=2.0, max_decel_mps2=8.0,
    max_jerk_mps3=10.0, steer_time_constant_s=0.1, steer_dead_time_s=0.05, max_steer_rad=0.55,
    max_steer_rate_radps=0.6, max_speed_mps=50.0, max_brake_pressure_bar=150.0,
    # A 1500 kg car, c_r 0.013 and c_d A 0.65 m2: about 0.25 m/s2 at 80 km/h.
    rolling_resistance_mps2=rolling_resistance_mps2(0.013), drag_1pm=drag_1pm(0.65, 1500.0),
)

# A loaded tractor-trailer: slow engine and air brakes (lag 0.8 s, dead time 0.3 s), 0.8 m/s2 at full
# throttle, 5 m/s2 service braking at about 8 bar.
TRUCK = VehicleProfile(
    length_m=12.0, width_m=2.55, height_m=3.8, wheelbase_m=6.0, track_width_m=2.05, rear_overhang_m=3.0,
    accel_time_constant_s=0.8, accel_dead_time_s=0.3, max_accel_mps2=0.8, max_decel_mps2=5.0,
    max_jerk_mps3=4.0, steer_time_constant_s=0.2, steer_dead_time_s=0.1, max_steer_rad=0.6,
    max_steer_rate_radps=0.3, max_speed_mps=25.0, max_brake_pressure_bar=8.0,
    # An 18 t tractor-trailer, c_r 0.007 and c_d A 5.5 m2.
    rolling_resistance_mps2=rolling_resistance_mps2(0.007), drag_1pm=drag_1pm(5.5, 18000.0),
)

PROFILES: dict[ProfileName, VehicleProfile] = {ProfileName.PASSENGER_CAR: PASSENGER_CAR, ProfileName.TRUCK: TRUCK}
