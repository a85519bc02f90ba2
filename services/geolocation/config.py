"""Configuration of the geolocation service (GeolocationConfig) and of its logic (units in the field names)."""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field, model_validator

from coopdrive.can.adapter import MountPoint, VehicleCanPath, load_adapter
from coopdrive.can.vehicle_port import VehicleCanPortConfig
from coopdrive.geodesy import GeodeticOrigin
from coopdrive.runtime.service import ServiceConfig
from coopdrive.services.geolocation.ekf import FIX_MODE_STD_M
from coopdrive.services.geolocation.motion_models import MotionModelKind, ProcessNoise
from coopdrive.v1 import gnss_pb2
from coopdrive.gnss.nmea_decoder import SentenceType
from coopdrive.vehicle import VehicleDescription, VehicleKind, vehicle_of


# A roof antenna about a metre ahead of the rear axle: what the geolocator assumed before a car's file could say.
DEFAULT_ANTENNA_X_M = 1.0


class FixModeStd(BaseModel):
    """A fix's horizontal noise by fix mode (GGA quality), one sigma, m. Defaults: Heudiasyc Table 1 (NovAtel
    APN-051, "~x" read as one sigma, "< x" as two), a NovAtel receiver's figures: a receiver that does better
    (a modern u-blox single fix is nearer 1-2 m; the RAV4's fixes lie 0.42 m RMS off comma's reference) wants its own."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    single_m: float = Field(FIX_MODE_STD_M[gnss_pb2.FIX_MODE_SINGLE], gt=0.0)
    sbas_m: float = Field(FIX_MODE_STD_M[gnss_pb2.FIX_MODE_SBAS], gt=0.0)
    dgps_m: float = Field(FIX_MODE_STD_M[gnss_pb2.FIX_MODE_DGPS], gt=0.0)
    rtk_float_m: float = Field(FIX_MODE_STD_M[gnss_pb2.FIX_MODE_RTK_FLOAT], gt=0.0)
    rtk_fixed_m: float = Field(FIX_MODE_STD_M[gnss_pb2.FIX_MODE_RTK_FIXED], gt=0.0)

    def by_mode(self) -> dict[int, float]:
        return {gnss_pb2.FIX_MODE_SINGLE: self.single_m, gnss_pb2.FIX_MODE_SBAS: self.sbas_m,
                gnss_pb2.FIX_MODE_DGPS: self.dgps_m, gnss_pb2.FIX_MODE_RTK_FLOAT: self.rtk_float_m,
                gnss_pb2.FIX_MODE_RTK_FIXED: self.rtk_fixed_m}


class GeolocatorConfig(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    vehicle_id: str = ""
    map_name: str = "a270"
    motion_model: MotionModelKind = MotionModelKind.CTRA
    # Vehicle geometry: rear-wheel track for eq. 8, wheelbase for the bicycle model (None: the vehicle's
    # description, coopdrive/vehicle; set for a car measured by hand).
    track_width_m: float | None = Field(None, gt=0.0)
    wheelbase_m: float | None = Field(None, gt=0.0)
    # The GNSS antenna, metres ahead of and left of the middle of the rear axle (the published ego state's point).
    # None: the car's vehicle CAN adapter file says (its mounting.gnss_antenna), else DEFAULT_ANTENNA_X_M ahead.
    antenna_x_m: float | None = None
    antenna_y_m: float | None = None
    # A fix's position noise (one sigma) by its mode when the receiver sends no GST, and its floor when it does.
    gnss_fix_std_m: FixModeStd = FixModeStd()
    # The part of a fix's error that is time-correlated (satellite orbits and clocks, the atmosphere, slowly
    # changing multipath): a first-order Gauss-Markov error of this steady-state std and correlation time, added
    # to the white noise above (Groves sect. 9.4 and 14.2.7). 0: the fixes' errors are taken as white, and a
    # filter averaging many fixes believes itself far better than a receiver's slowly wandering error allows.
    gnss_error_std_m: float = Field(0.01, ge=0.0)
    gnss_error_time_s: float = Field(60.0, gt=0.0)
    # When the fix mode changes, the correlated error starts again as a new one of the larger of the std above and
    # the new fix's (ekf.py): an RTK-float episode's error is then not averaged into the position as if it were
    # white (on a 10 s episode 0.4 m off: 0.36 m error and NEES 18 without, 2 cm and NEES 0.1 with).
    gnss_error_by_fix_mode: bool = True
    # The error of the fixes' time stamps (receiver latency as configured against as it is, the host's arrival
    # time resolution): a first-order Gauss-Markov error of this steady-state std and correlation time, which
    # puts a fix behind or ahead of the car by speed times it (ekf.py). 0: the stamps are taken as exact.
    gnss_time_error_std_s: float = Field(0.005, ge=0.0)
    gnss_time_error_time_s: float = Field(600.0, gt=0.0)
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
    # With the wheels too, the receiver's course over ground (above min_course_speed_mps) is fused as well: it
    # holds the heading where the fixes alone tell it slowly, and teaches the yaw-rate sensor's bias in seconds
    # (on the RAV4 drive, heading RMS 0.24 -> 0.18 deg, docs/tutorials/score-a-drive.md).
    course_with_odometry: bool = False
    gnss_heading_std_deg: float = Field(0.5, gt=0.0)
    # Fixes farther than this from the local frame's origin are refused (a wrong origin, not a drive).
    max_origin_distance_m: float = Field(100_000.0, gt=0.0)

    def process_noise(self) -> ProcessNoise:
        return ProcessNoise(self.jerk_std_mps3, self.yaw_accel_std_radps2, self.position_process_std_mps,
                            self.steering_std_rad, self.imu_yaw_rate_bias_walk_radps, self.imu_accel_bias_walk_mps2,
                            self.gnss_error_std_m, self.gnss_error_time_s, self.gnss_time_error_std_s,
                            self.gnss_time_error_time_s)

    def of_vehicle(self, vehicle: VehicleDescription, antenna: MountPoint | None = None) -> GeolocatorConfig:
        """With the geometry this config leaves open taken from the vehicle's description and, for the antenna,
        from its vehicle CAN adapter's mounting (None: the default)."""
        antenna = antenna or MountPoint(x_m=DEFAULT_ANTENNA_X_M)
        return self.model_copy(update={
            "track_width_m": self.track_width_m or vehicle.track_width_m,
            "wheelbase_m": self.wheelbase_m or vehicle.wheelbase_m,
            "antenna_x_m": antenna.x_m if self.antenna_x_m is None else self.antenna_x_m,
            "antenna_y_m": antenna.y_m if self.antenna_y_m is None else self.antenna_y_m})


class GnssInput(enum.Enum):
    """Where the GNSS data come from."""

    # The port when gnss_port is set, else whichever of gnss/nmea (an imported log, another driver) and
    # gnss/fix (the simulator) the bus carries.
    AUTO = "auto"
    # gnss_port (under replay, which opens no hardware: the gnss/nmea chunks the port delivered when recorded).
    PORT = "port"
    # NMEA bytes on the gnss/nmea topic, decoded here.
    NMEA_TOPIC = "nmea_topic"
    # Decoded fixes on the gnss/fix topic.
    FIX_TOPIC = "fix_topic"


class SerialSync(enum.Enum):
    """How the GNSS port's bytes enter the service's step order."""

    # Vehicle (wall clock): a reader thread hands chunks on as they arrive.
    FREE = "free"
    # Simulated clock: read up to each gnss/serial_mark from the simulator, so fixes land at the same step every run.
    MARKS = "marks"


class GeolocationConfig(ServiceConfig):
    # The vehicle whose geometry the motion model and the odometry take (where geolocator leaves it open).
    vehicle: VehicleKind = VehicleKind.PASSENGER_CAR
    geolocator: GeolocatorConfig = GeolocatorConfig()
    # Lane map (a shipped name such as "a270" or a GeoJSON path) for lane matching; its origin is the local frame.
    # None: no lane matching (lane.matched stays false), e.g. a road no map holds.
    map_name: str | None = None
    # The local frame's origin, only when there is no map; None: the first fix's position (logged).
    origin: GeodeticOrigin | None = None
    output_rate_hz: float = Field(50.0, gt=0.0)
    use_imu: bool = True
    gnss_input: GnssInput = GnssInput.AUTO
    # The GNSS receiver's NMEA port: a device or a pyserial URL (socket://host:port, rfc2217://host:port).
    # Every chunk read from it is published on gnss/nmea, stamped on arrival, and decoded from that stream.
    gnss_port: str | None = None
    gnss_baudrate: int = Field(115200, gt=0)
    serial_sync: SerialSync = SerialSync.FREE
    gnss_open_timeout_s: float = Field(10.0, gt=0.0)  # the simulator may create the port after we start
    serial_mark_timeout_s: float = Field(2.0, gt=0.0)
    # A fix is emitted once all these sentences of an epoch arrived (else when the next epoch starts).
    gnss_sentences: frozenset[SentenceType] = frozenset(
        {SentenceType.GGA, SentenceType.RMC, SentenceType.GST, SentenceType.VTG})
    # How long after its epoch the receiver puts a fix on the wire (its datasheet's output latency). A fix is
    # fused at its arrival minus this: left at 0, the estimate trails the car by speed times the latency.
    gnss_receiver_latency_s: float = Field(0.0, ge=0.0)
    # An epoch with a position still lacking some sentence this long after its first one is emitted anyway.
    gnss_epoch_wait_s: float = Field(0.5, gt=0.0)
    # The vehicle's CAN bus (python-can) with the VEH_ odometry frames; None: the frames come from the
    # can/vehicle topic (simulation, replay).
    can_port: VehicleCanPortConfig | None = None
    # The car's vehicle CAN adapter (coopdrive/can/adapter.py): where its bus carries wheel speeds, yaw rate,
    # steering; None: the simulator's car.
    vehicle_can: VehicleCanPath = None
    # How long after measuring them the car puts wheel speeds and yaw rate on the bus, and the IMU its samples.
    can_latency_s: float = Field(0.005, ge=0.0)
    imu_latency_s: float = Field(0.005, ge=0.0)

    def antenna_m(self) -> tuple[float, float]:
        """The GNSS antenna's lever arm (x, y) this config comes to: its geolocator keys, else the car's vehicle CAN
        adapter file, else the default. VehicleCanAdapterError when the file cannot be read."""
        resolved = self.geolocator.of_vehicle(vehicle_of(self.vehicle),
                                              load_adapter(self.vehicle_can)[0].mounting.gnss_antenna)
        return resolved.antenna_x_m, resolved.antenna_y_m

    @model_validator(mode="after")
    def _one_source_of_the_frame(self) -> GeolocationConfig:
        # Compared by value, not by which keys were given, so a recorded full config loads again.
        if self.map_name is not None and self.origin is not None:
            raise ValueError("origin is only used without a map: the map brings its own origin")
        if self.gnss_input is GnssInput.PORT and self.gnss_port is None:
            raise ValueError("gnss_input: port needs gnss_port")
        if self.geolocator.map_name != GeolocatorConfig().map_name:
            raise ValueError("geolocator.map_name is not read by the service: set map_name instead")
        return self
