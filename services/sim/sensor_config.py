"""Configuration of the simulated sensors: noise, rate, latency and dropout, units in field names."""
from __future__ import annotations

import enum
import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.v1 import gnss_pb2


class FixModeName(enum.Enum):
    """Fix modes as written in scenario files, mapped onto gnss_pb2.FixMode by `proto`."""

    NO_FIX = "no_fix"
    SINGLE = "single"
    SBAS = "sbas"
    DGPS = "dgps"
    RTK_FLOAT = "rtk_float"
    RTK_FIXED = "rtk_fixed"

    @property
    def proto(self) -> int:
        return gnss_pb2.FixMode.Value(f"FIX_MODE_{self.name}")


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class SensorTimingConfig(_Strict):
    rate_hz: float = Field(gt=0)
    latency_s: float = Field(default=0.0, ge=0)
    # Probability that one sample is lost (never delivered).
    dropout_probability: float = Field(default=0.0, ge=0, le=1)


class GnssConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=20.0, latency_s=0.02)
    fix_mode: FixModeName = FixModeName.RTK_FIXED
    # Multiplies the fix mode's accuracy: 0 gives a perfect receiver, 2 a poor sky view.
    accuracy_scale: float = Field(default=1.0, ge=0)
    # First-order Gauss-Markov correlation of the position error; 0 gives white noise.
    error_correlation_time_s: float = Field(default=0.0, ge=0)
    speed_sigma_mps: float = Field(default=0.03, ge=0)
    course_sigma_deg: float = Field(default=0.2, ge=0)
    talker_id: str = Field(default="GN", min_length=2, max_length=2)
    # GGA quality of an SBAS fix: 9 as NovAtel receivers (Heudiasyc), 2 as u-blox and NMEA 4.x.
    sbas_gga_quality: Literal[2, 9] = 9
    # Antenna position in the ego frame (x forward of the rear axle, y left).
    antenna_x_m: float = 0.0
    antenna_y_m: float = 0.0
    antenna_height_m: float = 1.5
    satellites: int = Field(default=14, ge=0)


class CanStateConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=100.0, latency_s=0.005)
    wheel_speed_sigma_mps: float = Field(default=0.02, ge=0)
    yaw_rate_sigma_radps: float = Field(default=0.002, ge=0)
    steering_sigma_rad: float = Field(default=0.0005, ge=0)


class ImuConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=100.0, latency_s=0.005)
    accel_sigma_mps2: float = Field(default=0.05, ge=0)
    yaw_rate_sigma_radps: float = Field(default=0.002, ge=0)
    # Constant biases of this unit (turn-on bias), as a fusion filter must estimate them.
    accel_bias_mps2: float = 0.0
    yaw_rate_bias_radps: float = 0.0


class RadarConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=20.0, latency_s=0.05)
    mount_x_m: float = 3.6
    mount_y_m: float = 0.0
    max_range_m: float = Field(default=200.0, gt=0)
    half_fov_rad: float = Field(default=math.radians(9.0), gt=0)
    max_tracks: int = Field(default=40, ge=1)
    range_sigma_m: float = Field(default=0.25, ge=0)
    azimuth_sigma_rad: float = Field(default=math.radians(0.3), ge=0)
    range_rate_sigma_mps: float = Field(default=0.12, ge=0)
    # Probability that a visible target is missing from one scan.
    miss_probability: float = Field(default=0.0, ge=0, le=1)


class LidarConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=12.5, latency_s=0.03)
    mount_x_m: float = 3.7
    mount_y_m: float = 0.0
    mount_height_m: float = 0.5
    # Four layers like a Sick LD-MRS, the third about parallel to the ground.
    layer_elevations_rad: list[float] = [math.radians(-1.2), math.radians(-0.4), math.radians(0.4),
                                         math.radians(1.2)]
    half_fov_rad: float = Field(default=math.radians(50.0), gt=0)
    azimuth_resolution_rad: float = Field(default=math.radians(0.5), gt=0)
    max_range_m: float = Field(default=200.0, gt=0)
    range_sigma_m: float = Field(default=0.05, ge=0)
    # Probability that one beam returns nothing.
    point_dropout_probability: float = Field(default=0.0, ge=0, le=1)


class CameraConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=15.0, latency_s=0.08)
    mount_x_m: float = 1.8
    mount_y_m: float = 0.0
    half_fov_rad: float = Field(default=math.radians(25.0), gt=0)
    max_range_m: float = Field(default=80.0, gt=0)
    position_sigma_m: float = Field(default=0.5, ge=0)
    lane_view_range_m: float = Field(default=40.0, gt=0)
    lane_offset_sigma_m: float = Field(default=0.05, ge=0)
    lane_heading_sigma_rad: float = Field(default=0.005, ge=0)
    miss_probability: float = Field(default=0.0, ge=0, le=1)


class SonarMount(_Strict):
    x_m: float
    y_m: float
    yaw_rad: float


def _default_sonar_mounts() -> list[SonarMount]:
    front_m, rear_m, half_width_m = 3.6, -0.9, 0.8
    return [
        SonarMount(x_m=front_m, y_m=half_width_m, yaw_rad=math.radians(30.0)),
        SonarMount(x_m=front_m, y_m=0.0, yaw_rad=0.0),
        SonarMount(x_m=front_m, y_m=-half_width_m, yaw_rad=math.radians(-30.0)),
        SonarMount(x_m=rear_m, y_m=half_width_m, yaw_rad=math.radians(150.0)),
        SonarMount(x_m=rear_m, y_m=0.0, yaw_rad=math.pi),
        SonarMount(x_m=rear_m, y_m=-half_width_m, yaw_rad=math.radians(-150.0)),
    ]


class SonarConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=10.0, latency_s=0.02)
    mounts: list[SonarMount] = Field(default_factory=_default_sonar_mounts)
    max_range_m: float = Field(default=4.0, gt=0)
    half_beam_rad: float = Field(default=math.radians(30.0), gt=0)
    rays_per_beam: int = Field(default=9, ge=1)
    range_sigma_m: float = Field(default=0.02, ge=0)


class SensorSuiteConfig(_Strict):
    gnss: GnssConfig = GnssConfig()
    can_state: CanStateConfig = CanStateConfig()
    imu: ImuConfig = ImuConfig()
    radar: RadarConfig = RadarConfig()
    lidar: LidarConfig = LidarConfig()
    camera: CameraConfig = CameraConfig()
    sonar: SonarConfig = SonarConfig()
