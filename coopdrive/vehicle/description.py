"""VehicleDescription: what a vehicle is (body, mass, driving resistance, powertrain and steering), with units in the
field names. The one description the simulator's plant, geolocation's motion model and control's laws all read
(coopdrive/vehicle/catalogue.py holds the car and the truck); where the simulated plant deliberately differs from
it, services/sim/plant.py says so as a perturbation."""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field

# ISA sea-level air: what the controllers' resistance feed-forward assumes.
AIR_DENSITY_KGPM3 = 1.225
# The controllers' resistance feed-forward has always taken g as 9.81 m/s2 (the simulated plant takes standard
# gravity, services/sim/plant.py): kept so their commands stay bit for bit; the 0.03 % lies far inside the rolling
# coefficient's own uncertainty.
FEEDFORWARD_GRAVITY_MPS2 = 9.81


class VehicleKind(enum.Enum):
    PASSENGER_CAR = "passenger_car"
    TRUCK = "truck"


class VehicleDescription(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    kind: VehicleKind
    # Body; the reference point is the rear axle centre.
    length_m: float = Field(gt=0)
    width_m: float = Field(gt=0)
    height_m: float = Field(gt=0)
    wheelbase_m: float = Field(gt=0)
    track_width_m: float = Field(gt=0)
    rear_overhang_m: float = Field(ge=0)
    mass_kg: float = Field(gt=0)
    # Driving resistance: c_d times the frontal area, and c_r.
    drag_area_m2: float = Field(gt=0)
    rolling_coefficient: float = Field(ge=0)
    # Driveline: first-order lag and dead time from an acceleration request to the acceleration (what the vehicle
    # announces as iCLCM responseTimeConstant / responseTimeDelay, and what the control laws compensate).
    response_time_constant_s: float = Field(gt=0)
    response_dead_time_s: float = Field(ge=0)
    # Acceleration at full throttle and deceleration at full brake: the same scale as actuation's PedalProfile
    # (accel_at_full_throttle_mps2, decel_at_full_brake_mps2), so its pedal map inverts the plant's.
    max_accel_mps2: float = Field(gt=0)
    max_decel_mps2: float = Field(gt=0)
    max_jerk_mps3: float = Field(gt=0)
    max_speed_mps: float = Field(gt=0)
    # Brake line pressure at full braking, reported on the CAN bus.
    max_brake_pressure_bar: float = Field(gt=0)
    # Steering: road-wheel angle lag, dead time and mechanical limits.
    steer_time_constant_s: float = Field(ge=0)
    steer_dead_time_s: float = Field(ge=0)
    max_steer_rad: float = Field(gt=0)
    max_steer_rate_radps: float = Field(gt=0)

    def resistance_accel_mps2(self, speed_mps: float) -> float:
        """Deceleration from rolling and aerodynamic resistance (Heudiasyc eq. 2), m/s2, >= 0 forwards."""
        aero_n = 0.5 * AIR_DENSITY_KGPM3 * self.drag_area_m2 * speed_mps * abs(speed_mps)
        rolling_n = self.rolling_coefficient * self.mass_kg * FEEDFORWARD_GRAVITY_MPS2 if speed_mps > 0 else 0.0
        return (aero_n + rolling_n) / self.mass_kg

    @property
    def front_bumper_x_m(self) -> float:
        """The front bumper, ahead of the rear axle."""
        return self.length_m - self.rear_overhang_m
