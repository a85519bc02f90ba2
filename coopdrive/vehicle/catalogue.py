"""The vehicles a scenario can drive: a passenger car and a loaded tractor-trailer, each described once."""

from __future__ import annotations

from coopdrive.vehicle.description import VehicleDescription, VehicleKind

# DRIVERTIVE's car reached 1.6-1.8 m/s2 at full throttle and GCDC capped requests at 2 m/s2. A 1500 kg car, c_r
# 0.012 and c_d A 0.7 m2.
PASSENGER_CAR = VehicleDescription(
    kind=VehicleKind.PASSENGER_CAR, length_m=4.5, width_m=1.8, height_m=1.5, wheelbase_m=2.7, track_width_m=1.55,
    rear_overhang_m=0.9, mass_kg=1500.0, drag_area_m2=0.7, rolling_coefficient=0.012,
    response_time_constant_s=0.3, response_dead_time_s=0.05, max_accel_mps2=2.0, max_decel_mps2=8.0,
    max_jerk_mps3=10.0, max_speed_mps=50.0, max_brake_pressure_bar=150.0, steer_time_constant_s=0.1,
    steer_dead_time_s=0.05, max_steer_rad=0.55, max_steer_rate_radps=0.6,
)

# An 18 t tractor-trailer, c_r 0.007 and c_d A 5.5 m2: slow engine and air brakes, 0.8 m/s2 at full throttle, 5 m/s2
# service braking at about 8 bar. One wheelbase for its kinematic bicycle (6 m; control once steered with 4.5 m
# while the simulator and geolocation used 6 m).
TRUCK = VehicleDescription(
    kind=VehicleKind.TRUCK, length_m=12.0, width_m=2.55, height_m=3.8, wheelbase_m=6.0, track_width_m=2.05,
    rear_overhang_m=3.0, mass_kg=18000.0, drag_area_m2=5.5, rolling_coefficient=0.007,
    response_time_constant_s=0.5, response_dead_time_s=0.1, max_accel_mps2=0.8, max_decel_mps2=5.0,
    max_jerk_mps3=4.0, max_speed_mps=25.0, max_brake_pressure_bar=8.0, steer_time_constant_s=0.2,
    steer_dead_time_s=0.1, max_steer_rad=0.6, max_steer_rate_radps=0.3,
)

VEHICLES: dict[VehicleKind, VehicleDescription] = {vehicle.kind: vehicle for vehicle in (PASSENGER_CAR, TRUCK)}


def vehicle_of(kind: VehicleKind) -> VehicleDescription:
    return VEHICLES[kind]
