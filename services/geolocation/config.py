"""Configuration of the geolocation logic (units in the field names)."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.services.geolocation.motion_models import MotionModelKind
from coopdrive.vehicle import VehicleDescription


class GeolocatorConfig(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    vehicle_id: str = ""
    map_name: str = "a270"
    motion_model: MotionModelKind = MotionModelKind.CTRA
    # Vehicle geometry: rear-wheel track for eq. 8, wheelbase for the bicycle model (None: the vehicle's
    # description, coopdrive/vehicle; set for a car measured by hand), antenna from the rear axle.
    track_width_m: float | None = Field(None, gt=0.0)
    wheelbase_m: float | None = Field(None, gt=0.0)
    antenna_x_m: float = 1.0
    antenna_y_m: float = 0.0
    # Sensor noise (one sigma).
    wheel_speed_std_mps: float = Field(0.01, gt=0.0)
    imu_yaw_rate_std_radps: float = Field(0.005, gt=0.0)
    imu_accel_std_mps2: float = Field(0.1, gt=0.0)
    use_imu_accel: bool = True
    # The inertial unit's biases are estimated (motion_models.py): a prior spread at turn-on wide enough for an
    # automotive MEMS unit (engineering estimate, about 0.3 deg/s and 10 mg; the simulated unit draws 0.001 rad/s
    # and 0.03 m/s^2, docs/real-world.md), then a slow walk (bias instability).
    imu_yaw_rate_bias_std_radps: float = Field(0.005, gt=0.0)
    imu_accel_bias_std_mps2: float = Field(0.1, gt=0.0)
    imu_yaw_rate_bias_walk_radps: float = Field(1e-4, ge=0.0)
    imu_accel_bias_walk_mps2: float = Field(1e-3, ge=0.0)
    # Process noise spectral densities.
    jerk_std_mps3: float = Field(0.5, gt=0.0)
    yaw_accel_std_radps2: float = Field(0.02, gt=0.0)
    # A yaw rate refused by the gate this long, every sample of it, is taken as measured: the car turned faster
    # than the yaw acceleration above allows (a sharp lane change at walking pace, merge seed 3), and a filter
    # that refuses its gyro and wheels loses its heading, then every fix.
    yaw_rate_reset_after_s: float = Field(0.1, gt=0.0)
    position_process_std_mps: float = Field(0.02, ge=0.0)
    steering_std_rad: float = Field(0.002, ge=0.0)
    # Standard deviation of a fix's latency around the configured one (serial line, scheduling): its position
    # is uncertain by speed times this along the track.
    gnss_time_jitter_s: float = Field(0.0, ge=0.0)
    # Gating and recovery.
    gate_probability: float = Field(0.999, gt=0.5, lt=1.0)
    gnss_reset_after_s: float = Field(3.0, gt=0.0)
    # ... counted since the last step of this much between consecutive refused RTK fixes (gated_fixes.py): multipath
    # jumps, a drifted filter sees the fixes move smoothly.
    gnss_reset_consistency_m: float = Field(0.5, gt=0.0)
    # ... and only when the filter could have drifted that far: the fixes are within this many of its own position
    # std or of the std of the fix it last fused (a DGPS bias it followed). A receiver in multipath sits metres off
    # in its claimed mode for seconds (docs/real-world.md), smoothly, while wheels and IMU keep the filter within
    # centimetres: resetting to it would move the car out of its lane.
    gnss_reset_sigmas: float = Field(5.0, gt=0.0)
    # A disagreement the filter's uncertainty cannot explain resets the position only after this long.
    gnss_reset_unexplained_after_s: float = Field(20.0, gt=0.0)
    # Latency: inputs older than the newest by up to history_s are fused at their sample time.
    compensate_latency: bool = True
    history_s: float = Field(1.0, gt=0.0)
    # Localisation mode thresholds.
    precise_std_m: float = Field(0.3, gt=0.0)
    lost_std_m: float = Field(5.0, gt=0.0)
    gnss_timeout_s: float = Field(0.5, gt=0.0)
    # Initial uncertainties when the first fix arrives.
    initial_heading_std_rad: float = Field(0.2, gt=0.0)
    initial_speed_std_mps: float = Field(1.0, gt=0.0)
    min_course_speed_mps: float = Field(2.0, ge=0.0)  # course over ground below this speed is noise
    # A receiver alone (no odometry for odometry_timeout_s): its speed (RMC/VTG) and, once moving faster than
    # min_course_speed_mps, its course over ground are fused. A dual-antenna heading (HDT/THS) always is.
    odometry_timeout_s: float = Field(1.0, gt=0.0)
    gnss_speed_std_mps: float = Field(0.1, gt=0.0)
    gnss_course_std_deg: float = Field(3.0, gt=0.0)
    gnss_heading_std_deg: float = Field(0.5, gt=0.0)
    # Fixes farther than this from the local frame's origin are refused (a wrong origin, not a drive).
    max_origin_distance_m: float = Field(100_000.0, gt=0.0)

    def of_vehicle(self, vehicle: VehicleDescription) -> GeolocatorConfig:
        """With the geometry this config leaves open taken from the vehicle's description."""
        return self.model_copy(update={"track_width_m": self.track_width_m or vehicle.track_width_m,
                                       "wheelbase_m": self.wheelbase_m or vehicle.wheelbase_m})
