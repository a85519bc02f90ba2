"""Configuration of the scene service: front ends, tracking, confidence and V2V trust.

The Chalmers thesis (Svensson 2017, Sect. 3.5 and 4.3.1) fixes the shape of the confidence scheme
(values in [0, 1], -1 unknown, boosts on agreement, decay with time, a fade time per source) but
publishes no numbers: it says the truck "was mostly running on default values". The numbers below
are therefore ours, ordered the way the thesis ranks the sensors (LiDAR and radar most trusted,
camera good at class, sonar least trusted, V2V "from excellent to worthless" depending on the sender).
The LiDAR clustering numbers are Heudiasyc's (Fig. 12, Sect. 6).
"""

from __future__ import annotations

import math

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.can.adapter import VehicleCanPath
from coopdrive.can.vehicle_port import VehicleCanPortConfig
from coopdrive.geodesy import GeodeticOrigin
from coopdrive.runtime.service import ServiceConfig
from coopdrive.v1 import header_pb2


class SourceConfig(BaseModel):
    """How much one kind of sensor is trusted, and for how long."""

    model_config = ConfigDict(extra="forbid")

    # A property keeps its value this long after this source last supported it.
    fade_time_s: float = Field(gt=0.0)
    # Exponential decay of this source's support while no new reading arrives.
    decay_per_s: float = Field(ge=0.0)
    # Ceiling of the support one source alone can give a property.
    max_confidence: float = Field(gt=0.0, le=1.0)
    # Fraction of the remaining room to max_confidence gained by one fully matching reading.
    gain: float = Field(gt=0.0, le=1.0)


class LidarConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Heudiasyc Sect. 6: 5 points, 1 m between consecutive points, 4 m lane margin.
    min_points: int = Field(default=5, ge=1)
    max_gap_m: float = Field(default=1.0, gt=0.0)
    lane_margin_m: float = Field(default=4.0, gt=0.0)
    # Clusters further to the side than this are off the road (ego lane plus one lane each side).
    max_lateral_m: float = Field(default=6.0, gt=0.0)
    # Longer clusters are guard rails or walls, not vehicles.
    max_extent_m: float = Field(default=20.0, gt=0.0)
    # Layers used for objects and free space; Heudiasyc (Sect. 3.2) kept the two upper layers of the
    # four-layer LD-MRS, the lower two seeing the ground. Empty = all layers.
    object_layers: list[int] = Field(default_factory=lambda: [2, 3])
    # Beams without a return may be left out of a scan; inside this half angle that means free space.
    half_fov_rad: float = Field(default=math.radians(50.0), gt=0.0)
    range_std_m: float = Field(default=0.1, gt=0.0)
    bearing_std_rad: float = Field(default=0.005, gt=0.0)
    # A cluster narrower than this is a partly seen vehicle, whose centre is correspondingly uncertain.
    typical_width_m: float = Field(default=1.8, gt=0.0)
    # Where the scanner sits, ahead of the rear axle (the scan's points are given from the rear axle);
    # None: on the front bumper. Its field of view fans out from here.
    mount_x_m: float | None = None
    # A cluster reaching this close to the edge of the field of view is cut by it: the vehicle's rear
    # may lie anywhere up to a typical length further back (a car sliding past on the flank).
    fov_edge_margin_rad: float = Field(default=math.radians(1.5), ge=0.0)
    typical_length_m: float = Field(default=4.5, gt=0.0)


class RadarConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    range_std_m: float = Field(default=0.3, gt=0.0)
    bearing_std_rad: float = Field(default=0.01, gt=0.0)
    range_rate_std_mps: float = Field(default=0.2, gt=0.0)
    # The radar reports the nearest point of a target (the simulator does), not its rear centre.
    reports_nearest_point: bool = True
    default_width_m: float = Field(default=1.8, gt=0.0)
    half_fov_rad: float = Field(default=math.radians(9.0), gt=0.0)
    max_range_m: float = Field(default=150.0, gt=0.0)


class CameraConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Chalmers 4.3.1: camera direction is a bit less trusted than LiDAR, distance even less.
    range_std_fraction: float = Field(default=0.08, gt=0.0)
    min_range_std_m: float = Field(default=0.5, gt=0.0)
    bearing_std_rad: float = Field(default=0.02, gt=0.0)
    # The detector reports the nearest point of a vehicle (the simulator does), not its rear centre.
    reports_nearest_point: bool = True
    default_width_m: float = Field(default=1.8, gt=0.0)


class LaneFusionConfig(BaseModel):
    """Map and camera lane fusion (ego_lane.py)."""

    model_config = ConfigDict(extra="forbid")

    # A lane camera's lateral position of a marking: about 0.1 m (engineering estimate of the order reported for
    # series lane-keeping cameras; the simulator's camera draws 0.05 m per marking), divided by its quality.
    camera_offset_std_m: float = Field(default=0.1, gt=0.0)
    camera_heading_std_rad: float = Field(default=0.01, gt=0.0)
    # The map's centre line itself (survey and digitisation), beside the position estimate's error.
    map_offset_std_m: float = Field(default=0.1, gt=0.0)
    map_heading_std_rad: float = Field(default=0.005, gt=0.0)
    # Map and camera offsets further apart than this many standard deviations of their difference disagree.
    gate_sigma: float = Field(default=3.0, gt=0.0)
    min_marking_quality: float = Field(default=0.3, gt=0.0, le=1.0)
    max_marking_age_s: float = Field(default=0.3, gt=0.0)
    # A marking pair further apart or closer than these is not one lane.
    min_lane_width_m: float = Field(default=2.2, gt=0.0)
    max_lane_width_m: float = Field(default=5.0, gt=0.0)
    boundary_view_range_m: float = Field(default=40.0, gt=0.0)


class SonarConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    range_std_m: float = Field(default=0.3, gt=0.0)
    # Half opening angle of the sonar cone: the echo can come from anywhere inside it.
    half_beam_rad: float = Field(default=0.3, gt=0.0)


class V2vConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    position_std_m: float = Field(default=0.7, gt=0.0)
    speed_std_mps: float = Field(default=0.3, gt=0.0)
    accel_std_mps2: float = Field(default=0.5, gt=0.0)
    # ETSI CAM reference point is the centre of the vehicle's front; the scene tracks rear bumpers.
    reference_is_front: bool = True
    default_length_m: float = Field(default=4.5, gt=0.0)


class TrustConfig(BaseModel):
    """Per-station V2V trust, in [0, 1]."""

    model_config = ConfigDict(extra="forbid")

    initial: float = Field(default=0.6, ge=0.0, le=1.0)
    # Below this a station's kinematics are not fused and its V2V-only object is never an obstacle.
    min_trusted: float = Field(default=0.4, ge=0.0, le=1.0)
    # Position disagreement with our own sensors beyond which the station is losing trust.
    agree_m: float = Field(default=1.5, gt=0.0)
    drop_per_s: float = Field(default=0.5, gt=0.0)
    raise_per_s: float = Field(default=0.05, gt=0.0)
    # Longest interval credited to one message, so a silent station is not judged on a gap.
    max_step_s: float = Field(default=0.5, gt=0.0)
    # A station is linked to a LiDAR/radar track this close even outside the fusion gate, so that an
    # offset station is caught disagreeing instead of spawning a second object; below a rear-to-rear
    # distance of a car length plus a gap, so the next vehicle of a platoon is not taken.
    link_gate_m: float = Field(default=4.0, gt=0.0)
    # Radius around a claim within which a radar track counts as seeing it.
    radar_match_m: float = Field(default=2.5, gt=0.0)
    # A V2V claim compared with sensor data older than this is not compared at all.
    max_sensor_age_s: float = Field(default=0.3, gt=0.0)
    # Floor of the weight a V2V reading gets in confidence: an untrusted station still keeps its own
    # V2V-only object (flagged) and its station id alive, at low confidence.
    min_support_weight: float = Field(default=0.1, gt=0.0, le=1.0)
    # One free-space contradiction costs this much at once; this many make the station a ghost.
    ghost_penalty: float = Field(default=0.3, ge=0.0, le=1.0)
    ghost_hits: int = Field(default=2, ge=1)
    max_speed_mps: float = Field(default=70.0, gt=0.0)
    max_abs_accel_mps2: float = Field(default=12.0, gt=0.0)
    max_length_m: float = Field(default=25.0, gt=0.0)
    # Reported position may move this much more than the reported speed explains between messages.
    jump_tolerance_m: float = Field(default=3.0, gt=0.0)
    # Free-space test: the claim is free if beams pass this far beyond it.
    free_margin_m: float = Field(default=1.0, gt=0.0)
    # Within this range a radar or camera object the LiDAR looks through (its beams reach past it) and does not
    # see itself is no MIO: a false track, or a car's readings split off beside it (the LiDAR's reach on dark
    # cars, an engineering estimate, bounds where its silence means anything).
    lidar_veto_range_m: float = Field(default=60.0, ge=0.0)


class FrontFaceConfig(BaseModel):
    """When a tracked vehicle shows our sensors its front rather than its rear (front_faces.py)."""

    model_config = ConfigDict(extra="forbid")

    # Below this the filter's velocity is too uncertain to tell where a vehicle points (a tracked car's speed
    # settles to a few tenths of a m/s).
    min_speed_mps: float = Field(default=3.0, gt=0.0)
    # ... and while its heading is less certain than this (a LiDAR track settles at 0.04-0.05 rad at 12 m/s).
    max_heading_std_rad: float = Field(default=0.15, gt=0.0)
    # A vehicle moving within this angle of the line to the sensor shows it its front ...
    facing_angle_rad: float = Field(default=1.05, gt=0.0)
    # ... until it moves more than this off that line: beside us, it shows its flank.
    release_angle_rad: float = Field(default=1.40, gt=0.0)


class TrackingConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Chi-square 99 % for two degrees of freedom (range, bearing).
    gate_chi2: float = Field(default=9.21, gt=0.0)
    # Chi-square 99 % for one degree of freedom: a radar reading's range rate against a track's (doppler_gate.py).
    doppler_gate_chi2: float = Field(default=6.63, gt=0.0)
    # ... and never tighter than this: a track's speed lags a hard brake's onset by more than its covariance says.
    doppler_gate_min_mps: float = Field(default=2.0, ge=0.0)
    # Chalmers 4.3.1: matching by direction and distance "with a slight emphasis on the angle".
    angle_emphasis: float = Field(default=1.2, ge=1.0)
    # White-jerk spectral density of the constant-acceleration model.
    jerk_psd_m2ps5: float = Field(default=2.0, gt=0.0)
    initial_speed_std_mps: float = Field(default=10.0, gt=0.0)
    initial_accel_std_mps2: float = Field(default=3.0, gt=0.0)
    confirm_hits: int = Field(default=3, ge=1)
    # A tentative track with no hit for this long is deleted; it was never published.
    tentative_timeout_s: float = Field(default=0.3, gt=0.0)
    # Measurements are kept this long per track for out-of-sequence replay.
    replay_window_s: float = Field(default=1.5, gt=0.0)
    # Chalmers 4.3.1: distance updated "with a bias for closer readings": R is divided by this.
    closer_bias: float = Field(default=1.5, ge=1.0)
    # Chalmers 4.3.1: property values blend "with a heavy bias for new data".
    new_data_bias: float = Field(default=3.0, gt=0.0)
    # Support given to speed and heading by sensors that only see positions (the filter derives them).
    derived_quality: float = Field(default=0.5, ge=0.0, le=1.0)
    # Two cars' rear bumper centres are never closer than a car is wide: confirmed tracks closer than this,
    # moving alike, are one vehicle whose readings split between them, and become one track.
    duplicate_distance_m: float = Field(default=1.5, gt=0.0)
    duplicate_speed_difference_mps: float = Field(default=1.5, gt=0.0)
    front_faces: FrontFaceConfig = Field(default_factory=FrontFaceConfig)


class SceneFusionConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Defaults: the simulator's passenger car profile.
    ego_length_m: float = Field(default=4.5, gt=0.0)
    # Rear axle to rear bumper; the front bumper is ego_length_m minus this ahead of the rear axle.
    ego_rear_overhang_m: float = Field(default=0.9, ge=0.0)
    # Half width of the MIO corridor is lidar.lane_margin_m / 2 (Heudiasyc Fig. 4).
    lidar: LidarConfig = Field(default_factory=LidarConfig)
    radar: RadarConfig = Field(default_factory=RadarConfig)
    camera: CameraConfig = Field(default_factory=CameraConfig)
    sonar: SonarConfig = Field(default_factory=SonarConfig)
    v2v: V2vConfig = Field(default_factory=V2vConfig)
    trust: TrustConfig = Field(default_factory=TrustConfig)
    lanes: LaneFusionConfig = Field(default_factory=LaneFusionConfig)
    tracking: TrackingConfig = Field(default_factory=TrackingConfig)
    lidar_source: SourceConfig = Field(
        default_factory=lambda: SourceConfig(fade_time_s=0.5, decay_per_s=0.4, max_confidence=0.9, gain=0.5))
    radar_source: SourceConfig = Field(
        default_factory=lambda: SourceConfig(fade_time_s=0.5, decay_per_s=0.4, max_confidence=0.9, gain=0.5))
    camera_source: SourceConfig = Field(
        default_factory=lambda: SourceConfig(fade_time_s=0.4, decay_per_s=0.6, max_confidence=0.7, gain=0.4))
    sonar_source: SourceConfig = Field(
        default_factory=lambda: SourceConfig(fade_time_s=0.3, decay_per_s=1.0, max_confidence=0.5, gain=0.3))
    v2v_source: SourceConfig = Field(
        default_factory=lambda: SourceConfig(fade_time_s=1.0, decay_per_s=0.2, max_confidence=0.7, gain=0.3))

    def source(self, source: int) -> SourceConfig:
        """The confidence settings of one header_pb2.SensorSource."""
        table = {
            header_pb2.SENSOR_SOURCE_LIDAR: self.lidar_source,
            header_pb2.SENSOR_SOURCE_RADAR: self.radar_source,
            header_pb2.SENSOR_SOURCE_CAMERA: self.camera_source,
            header_pb2.SENSOR_SOURCE_SONAR: self.sonar_source,
            header_pb2.SENSOR_SOURCE_V2V: self.v2v_source,
        }
        try:
            return table[source]
        except KeyError:
            raise ValueError(f"no confidence settings for sensor source {source}") from None


class SceneConfig(ServiceConfig):
    output_rate_hz: float = 25.0
    # Lanes come from this map when set; without one, lanes are bands along the ego heading.
    map_name: str | None = None
    # The local ENU frame's origin (used for V2V positions when no map is set).
    origin: GeodeticOrigin = GeodeticOrigin()
    # A station's iCLCM acceleration request older than this is not put on its object.
    intended_accel_max_age_s: float = Field(default=0.4, gt=0)
    fusion: SceneFusionConfig = Field(default_factory=SceneFusionConfig)
    # The CAN bus the radar's object lists arrive on (python-can); None: the can/vehicle topic (simulation).
    can_port: VehicleCanPortConfig | None = None
    # How long after measuring an object list the radar sends it (its cycle's processing time).
    radar_latency_s: float = Field(default=0.05, ge=0)
    # The car's vehicle CAN adapter (coopdrive/can/adapter.py); None: the simulator's car.
    vehicle_can: VehicleCanPath = None
