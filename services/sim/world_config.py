"""Configuration of the simulated world: vehicles, sensors, the local origin."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class VehicleSpec(_Strict):
    vehicle_id: str
    station_id: int = 0
    # Vehicles without a speed profile are driven by their stack's actuation commands.
    speed_profile: list[tuple[float, float]] = Field(default_factory=list)
    station_m: float = 0.0
    lateral_m: float = 0.0
    speed_mps: float = 15.0
    length_m: float = 4.5
    width_m: float = 1.8
    rear_overhang_m: float = 1.0
    wheelbase_m: float = 2.7
    track_width_m: float = 1.55
    accel_lag_s: float = 0.3
    # The passenger-car profile's accel_dead_time_s (profiles.py).
    dead_time_s: float = 0.1
    max_accel_mps2: float = 3.0
    max_decel_mps2: float = 8.0
    max_steering_rad: float = 0.5


class GnssSensorConfig(_Strict):
    rate_hz: float = 10.0
    sigma_m: float = 0.02
    latency_s: float = 0.0


class RadarSensorConfig(_Strict):
    rate_hz: float = 25.0
    range_sigma_m: float = 0.05
    range_rate_sigma_mps: float = 0.05
    max_range_m: float = 200.0
    half_fov_rad: float = 0.15


class CanSensorConfig(_Strict):
    rate_hz: float = 50.0
    wheel_speed_sigma_mps: float = 0.02
    yaw_rate_sigma_radps: float = 0.001


class WorldConfig(_Strict):
    origin_lat_deg: float = 51.4758
    origin_lon_deg: float = 5.6247
    origin_alt_m: float = 20.0
    lane_width_m: float = 3.5
    vehicles: list[VehicleSpec] = Field(default_factory=list)
    gnss: GnssSensorConfig = GnssSensorConfig()
    radar: RadarSensorConfig = RadarSensorConfig()
    can: CanSensorConfig = CanSensorConfig()
    ground_truth_rate_hz: float = 10.0
