"""Configuration of the simulated sensors: noise, rate, latency and dropout, units in field names.

The defaults are the real world: each error source a real device has, at a value taken from a datasheet or a
published measurement (services/sim/README.md names the source of each). `world_profile.py` holds the ideal
world (every error source off) that tests needing exact answers ask for with `--world ideal`.
"""
from __future__ import annotations

import enum
import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.v1 import gnss_pb2

# Where sensors sit when a configuration leaves their mount out: placed from the vehicle's profile.
CAMERA_BEHIND_FRONT_BUMPER_M = 2.0
SONAR_INSET_FROM_SIDE_M = 0.1
SONAR_CORNER_YAW_RAD = math.radians(30.0)


def front_bumper_x_m(profile: VehicleProfile) -> float:
    return profile.length_m - profile.rear_overhang_m


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
    # Standard deviation of a half-normal delay added to latency_s (bus arbitration, scheduling); samples still
    # arrive in the order they were taken.
    latency_jitter_s: float = Field(default=0.0, ge=0)


class GnssConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=20.0, latency_s=0.02, latency_jitter_s=0.005)
    fix_mode: FixModeName = FixModeName.RTK_FIXED
    # Multiplies the fix mode's accuracy: 0 gives a perfect receiver, 2 a poor sky view.
    accuracy_scale: float = Field(default=1.0, ge=0)
    # First-order Gauss-Markov correlation of the position error; 0 gives white noise.
    error_correlation_time_s: float = Field(default=60.0, ge=0)
    # Episodes in which the receiver loses its configured mode (RTK fixed to float or DGPS): mean rate and
    # mean length, both exponential; an episode falls one mode (DEGRADE_TWO_MODES_SHARE of them two).
    degradation_rate_per_h: float = Field(default=12.0, ge=0)
    degradation_mean_duration_s: float = Field(default=8.0, gt=0)
    # Multipath episodes: the fix jumps by about multipath_jump_m (random direction) while the receiver keeps
    # its mode. Rare under open sky, frequent beside a vehicle taller than the antenna within obstacle_range_m,
    # where a share of the episodes is an outage (no fix) instead.
    multipath_rate_per_h: float = Field(default=2.0, ge=0)
    multipath_near_obstacle_rate_per_h: float = Field(default=60.0, ge=0)
    multipath_jump_m: float = Field(default=1.5, ge=0)
    multipath_mean_duration_s: float = Field(default=2.0, gt=0)
    obstacle_range_m: float = Field(default=10.0, gt=0)
    near_obstacle_outage_share: float = Field(default=0.3, ge=0, le=1)
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
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=100.0, latency_s=0.005, latency_jitter_s=0.002)
    wheel_speed_sigma_mps: float = Field(default=0.02, ge=0)
    yaw_rate_sigma_radps: float = Field(default=0.002, ge=0)
    steering_sigma_rad: float = Field(default=0.0005, ge=0)


class ImuConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=100.0, latency_s=0.005, latency_jitter_s=0.002)
    accel_sigma_mps2: float = Field(default=0.05, ge=0)
    yaw_rate_sigma_radps: float = Field(default=0.002, ge=0)
    # Constant biases of this unit, as a fusion filter must estimate them: these fixed values plus a turn-on
    # bias drawn once per unit and run (normal, these standard deviations).
    accel_bias_mps2: float = 0.0
    yaw_rate_bias_radps: float = 0.0
    accel_turn_on_bias_sigma_mps2: float = Field(default=0.03, ge=0)
    yaw_rate_turn_on_bias_sigma_radps: float = Field(default=0.001, ge=0)


class RadarConfig(_Strict):
    # ARS 408-21: a cycle of about 72 ms.
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=13.9, latency_s=0.05, latency_jitter_s=0.005)
    # None: centre of the front bumper of the vehicle's profile.
    mount_x_m: float | None = None
    mount_y_m: float = 0.0
    max_range_m: float = Field(default=200.0, gt=0)
    half_fov_rad: float = Field(default=math.radians(9.0), gt=0)
    max_tracks: int = Field(default=40, ge=1)
    range_sigma_m: float = Field(default=0.2, ge=0)
    azimuth_sigma_rad: float = Field(default=math.radians(0.2), ge=0)
    range_rate_sigma_mps: float = Field(default=0.1, ge=0)
    # Calibration errors of this unit: a range offset and a mounting misalignment, the same every scan.
    range_bias_m: float = 0.1
    azimuth_bias_rad: float = math.radians(0.2)
    # Probability that a visible target is missing from one scan.
    miss_probability: float = Field(default=0.05, ge=0, le=1)
    # False tracks (stationary reflectors: signs, guardrail posts, manholes) per scan, Poisson, each lasting
    # one scan, placed uniformly in range and azimuth within the field of view.
    false_alarms_per_scan: float = Field(default=0.2, ge=0)
    # Probability per scan that the radar's tracker gives a target a new track id.
    track_id_switch_probability: float = Field(default=0.005, ge=0, le=1)
    # Two targets closer than both resolutions are reported as one track (the nearer's).
    range_resolution_m: float = Field(default=1.79, ge=0)
    azimuth_resolution_rad: float = Field(default=math.radians(1.0), ge=0)
    # The reported width is an estimate: the true width plus this noise (never below MIN_RADAR_WIDTH_M).
    width_sigma_m: float = Field(default=0.3, ge=0)

    def placed(self, profile: VehicleProfile = PASSENGER_CAR) -> RadarConfig:
        if self.mount_x_m is not None:
            return self
        return self.model_copy(update={"mount_x_m": front_bumper_x_m(profile)})


class LidarConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=12.5, latency_s=0.03, dropout_probability=0.002,
                                                    latency_jitter_s=0.005)
    # None: centre of the front bumper of the vehicle's profile.
    mount_x_m: float | None = None
    mount_y_m: float = 0.0
    mount_height_m: float = 0.5
    # Four layers like a Sick LD-MRS, the third about parallel to the ground.
    layer_elevations_rad: list[float] = [math.radians(-1.2), math.radians(-0.4), math.radians(0.4),
                                         math.radians(1.2)]
    half_fov_rad: float = Field(default=math.radians(50.0), gt=0)
    azimuth_resolution_rad: float = Field(default=math.radians(0.5), gt=0)
    max_range_m: float = Field(default=200.0, gt=0)
    range_sigma_m: float = Field(default=0.05, ge=0)
    # Probability that one beam returns nothing (dark paint, glancing incidence, spray).
    point_dropout_probability: float = Field(default=0.03, ge=0, le=1)
    # Probability that one beam returns a spurious echo (rain, spray, dust) at a uniform range short of its true one.
    clutter_probability: float = Field(default=0.002, ge=0, le=1)

    def placed(self, profile: VehicleProfile = PASSENGER_CAR) -> LidarConfig:
        if self.mount_x_m is not None:
            return self
        return self.model_copy(update={"mount_x_m": front_bumper_x_m(profile)})


class CameraConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=15.0, latency_s=0.08, latency_jitter_s=0.01)
    # None: behind the windscreen, CAMERA_BEHIND_FRONT_BUMPER_M behind the front bumper.
    mount_x_m: float | None = None
    mount_y_m: float = 0.0
    half_fov_rad: float = Field(default=math.radians(25.0), gt=0)
    max_range_m: float = Field(default=80.0, gt=0)
    # A monocular camera ranges a vehicle by the image row where it meets the road: its range error grows with the
    # square of the range, about 5 % at 45 m and 10 % at 90 m (Stein, Mano and Shashua, "Vision-based ACC with a
    # single camera", 2003), so sigma = max(min_range_sigma_m, range_sigma_per_m2 * range^2). Its bearing comes from
    # the image column, good to a few pixels: a third of a degree. (One isotropic 0.5 m for both was far too kind in
    # range at 40 m and ten times too rough across the beam at 10 m.)
    range_sigma_per_m2: float = Field(default=0.05 / 45.0, ge=0)
    min_range_sigma_m: float = Field(default=0.1, ge=0)
    bearing_sigma_rad: float = Field(default=math.radians(0.3), ge=0)
    lane_view_range_m: float = Field(default=40.0, gt=0)
    lane_offset_sigma_m: float = Field(default=0.05, ge=0)
    lane_heading_sigma_rad: float = Field(default=0.005, ge=0)
    miss_probability: float = Field(default=0.05, ge=0, le=1)
    # Probability that a detection carries another class than its own.
    misclassification_probability: float = Field(default=0.02, ge=0, le=1)
    width_sigma_m: float = Field(default=0.15, ge=0)

    def placed(self, profile: VehicleProfile = PASSENGER_CAR) -> CameraConfig:
        if self.mount_x_m is not None:
            return self
        return self.model_copy(update={"mount_x_m": front_bumper_x_m(profile) - CAMERA_BEHIND_FRONT_BUMPER_M})


class SonarMount(_Strict):
    x_m: float
    y_m: float
    yaw_rad: float


def sonar_mounts_for(profile: VehicleProfile) -> list[SonarMount]:
    """Three sonars on each bumper: the corners angled outwards, one in the middle."""
    front_m, rear_m = front_bumper_x_m(profile), -profile.rear_overhang_m
    side_m = profile.width_m / 2.0 - SONAR_INSET_FROM_SIDE_M
    corner = SONAR_CORNER_YAW_RAD
    return [
        SonarMount(x_m=front_m, y_m=side_m, yaw_rad=corner),
        SonarMount(x_m=front_m, y_m=0.0, yaw_rad=0.0),
        SonarMount(x_m=front_m, y_m=-side_m, yaw_rad=-corner),
        SonarMount(x_m=rear_m, y_m=side_m, yaw_rad=math.pi - corner),
        SonarMount(x_m=rear_m, y_m=0.0, yaw_rad=math.pi),
        SonarMount(x_m=rear_m, y_m=-side_m, yaw_rad=corner - math.pi),
    ]


class SonarConfig(_Strict):
    timing: SensorTimingConfig = SensorTimingConfig(rate_hz=10.0, latency_s=0.02, latency_jitter_s=0.005)
    # None: sonar_mounts_for(the vehicle's profile).
    mounts: list[SonarMount] | None = None
    max_range_m: float = Field(default=4.0, gt=0)
    half_beam_rad: float = Field(default=math.radians(30.0), gt=0)
    rays_per_beam: int = Field(default=9, ge=1)
    range_sigma_m: float = Field(default=0.02, ge=0)

    def placed(self, profile: VehicleProfile = PASSENGER_CAR) -> SonarConfig:
        if self.mounts is not None:
            return self
        return self.model_copy(update={"mounts": sonar_mounts_for(profile)})


class SensorSuiteConfig(_Strict):
    gnss: GnssConfig = GnssConfig()
    can_state: CanStateConfig = CanStateConfig()
    imu: ImuConfig = ImuConfig()
    radar: RadarConfig = RadarConfig()
    lidar: LidarConfig = LidarConfig()
    camera: CameraConfig = CameraConfig()
    sonar: SonarConfig = SonarConfig()

    def placed(self, profile: VehicleProfile) -> SensorSuiteConfig:
        """This configuration with every mount left out placed on the given vehicle."""
        return self.model_copy(update={"radar": self.radar.placed(profile), "lidar": self.lidar.placed(profile),
                                       "camera": self.camera.placed(profile), "sonar": self.sonar.placed(profile)})
