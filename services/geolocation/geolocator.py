"""Geolocator: GNSS fixes, CAN odometry and IMU samples in, EgoState at the rear axle out.

Fed by method calls carrying their sample times; deterministic (no clock, no randomness). Each input is
fused at its own sample time through a replay buffer (latency.py), so a late GNSS fix acts where the
vehicle was when it was measured. The ego state is then matched to the lane map.
"""

from __future__ import annotations

import enum
import math
from collections import Counter
from dataclasses import dataclass, replace

import numpy as np
from pymap3d.vincenty import vdist

from coopdrive.can.adapter import OdometryOptions
from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap import RoadMap
from coopdrive.services.geolocation.config import GeolocatorConfig
from coopdrive.vehicle import PASSENGER_CAR, VehicleDescription
from coopdrive.services.geolocation.ekf import GeolocationEkf, UpdateKind, gnss_position_std_m
from coopdrive.services.geolocation.gated_fixes import GatedFixes
from coopdrive.services.geolocation.frames import RTK_FIX_MODES, LeverArm, ModeThresholds, localisation_mode
from coopdrive.services.geolocation.latency import Insertion, ReplayBuffer
from coopdrive.services.geolocation.motion_models import (
    ACCEL, HEADING, SPEED, STATE_DIM, VEHICLE_STATE_DIM, YAW_RATE, CtraModel, E, KinematicBicycleModel,
    MotionModelKind, N, ProcessNoise,
)
from coopdrive.services.geolocation.odometry import Odometry, OdometrySample
from coopdrive.v1 import ego_pb2, gnss_pb2, vehicle_pb2

SENDER = "geolocation"
STATIONARY_SPEED_MPS = 0.5
# Rear wheels this slow are standing still (wheel-speed sensors read zero there, give or take their noise).
STANDSTILL_SPEED_MPS = 0.05
HEADING_FROM_TRACK_MIN_M = 2.0  # two fixes this far apart give a usable heading
PENDING_FIX_MAX_AGE_S = 5.0
INITIAL_YAW_RATE_STD_RADPS = 0.1
INITIAL_ACCEL_STD_MPS2 = 1.0
UNKNOWN_HEADING_STD_RAD = math.pi
NO_LEVER_ARM = LeverArm()
FIX_INTERVALS_FRESH = 1.5  # a fix is fresh until this many receiver intervals after it
# Until a second fix shows the receiver's rate, it is taken to be the slowest common one: a 1 Hz receiver's
# first fix must not be stale before its second can come.
ASSUMED_FIX_INTERVAL_S = 1.0


class InputEvent(enum.Enum):
    FIX_FUSED = "fix_fused"
    FIX_GATED = "fix_gated"
    FIX_WITHOUT_POSITION = "fix_without_position"
    FIX_INVALID = "fix_invalid"
    GNSS_RESET = "gnss_reset"
    YAW_RATE_RESET = "yaw_rate_reset"
    ODOMETRY_INVALID = "odometry_invalid"
    IMU_INVALID = "imu_invalid"
    TOO_OLD = "too_old"
    STANDSTILL = "standstill"
    FIX_FAR_FROM_ORIGIN = "fix_far_from_origin"


@dataclass(frozen=True)
class _Fix:
    east_m: float
    north_m: float
    std_east_m: float
    std_north_m: float
    fix_mode: int
    speed_mps: float
    course_deg: float
    velocity_valid: bool = False
    heading_rad: float | None = None  # dual-antenna heading, ENU


@dataclass(frozen=True)
class _Imu:
    yaw_rate_radps: float
    accel_mps2: float


@dataclass(frozen=True)
class _Bookkeeping:
    last_fix_time_s: float | None = None
    last_fix_mode: int = gnss_pb2.FIX_MODE_UNSPECIFIED
    # The fixes refused since the last fused one (None while fixes are fused).
    gated: GatedFixes | None = None
    pending_fix: tuple[float, _Fix] | None = None
    last_speed_mps: float | None = None
    # The car's latest yaw rate (its sensor's, else its wheels'): reported while there is no fix.
    last_yaw_rate_radps: float | None = None
    # False while the filter runs on a position alone (heading unknown, std pi): a heading found later
    # (dual antenna, course over ground, a track) then re-initialises it.
    heading_known: bool = False
    last_odometry_time_s: float | None = None
    # The reported std of the last fix fused. A DGPS or float solution's error is correlated over tens of seconds,
    # so an estimate that followed such fixes is off by about as much, however small its covariance (which
    # takes each fix's error as independent) has become.
    fused_fix_std_m: float = 0.0
    # Since when every yaw rate measured (gyro, wheels) has been refused by the gate (None: the last was fused).
    yaw_rate_refused_since_s: float | None = None


class Geolocator:
    def __init__(self, config: GeolocatorConfig, road_map: RoadMap | None = None,
                 origin: tuple[float, float, float] | None = None, first_fix_origin: bool = False,
                 vehicle: VehicleDescription = PASSENGER_CAR) -> None:
        """The local frame's origin: the road map's, else origin, else (first_fix_origin) the first fix's. vehicle:
        the geometry the config leaves open."""
        config = self.config = config.of_vehicle(vehicle)
        if road_map is None and origin is None and not first_fix_origin:
            road_map = RoadMap.load(config.map_name)
        self.road_map = road_map
        self.origin = origin if origin is not None or road_map is None else road_map.origin
        self.plane = LocalTangentPlane(*self.origin) if self.origin is not None else None
        # Distance of the first fix refused as too far from the origin (for the service's one log line).
        self.far_fix_distance_m: float | None = None
        # The receiver's fix interval (shortest seen): a 1 Hz receiver's fix is fresh for more than 0.5 s.
        self._fix_interval_s: float | None = None
        self._last_fix_input_s: float | None = None
        noise = ProcessNoise(config.jerk_std_mps3, config.yaw_accel_std_radps2, config.position_process_std_mps,
                             config.steering_std_rad, config.imu_yaw_rate_bias_walk_radps,
                             config.imu_accel_bias_walk_mps2)
        # The bicycle model turns by the steering angle: its yaw rate is not measured but follows the wheels.
        self._steered = config.motion_model is MotionModelKind.KINEMATIC_BICYCLE
        model = KinematicBicycleModel(noise, config.wheelbase_m) if self._steered else CtraModel(noise)
        self.ekf = GeolocationEkf(model, config.gate_probability)
        self.odometry = Odometry(config.track_width_m, config.wheel_speed_std_mps)
        self.lever_arm = LeverArm(config.antenna_x_m, config.antenna_y_m)
        self.thresholds = ModeThresholds(config.precise_std_m, config.lost_std_m, config.gnss_timeout_s)
        self.counters: Counter[InputEvent] = Counter()
        self._book = _Bookkeeping()
        self._buffer = ReplayBuffer(self._apply, self._snapshot, self._restore, config.history_s)
        self._sequence = 0

    def configure_odometry(self, options: OdometryOptions) -> None:
        """How this car's wheels are read (its vehicle CAN adapter's odometry options)."""
        self.odometry = Odometry(self.config.track_width_m, self.config.wheel_speed_std_mps, options)

    # --- inputs --------------------------------------------------------------------------------
    def on_gnss_fix(self, fix: gnss_pb2.GnssFix) -> Insertion | None:
        """A fix, fused at fix.header.sample_time_s. Returns how it was inserted, None if not usable."""
        stds = gnss_position_std_m(fix.fix_mode, fix.std_east_m, fix.std_north_m)
        if stds is None:
            self.counters[InputEvent.FIX_WITHOUT_POSITION] += 1
            return None
        if not (-90.0 <= fix.latitude_deg <= 90.0 and -180.0 <= fix.longitude_deg <= 180.0
                and all(map(math.isfinite, (fix.latitude_deg, fix.longitude_deg, fix.altitude_m)))):
            self.counters[InputEvent.FIX_INVALID] += 1
            return None
        self.odometry.on_gnss_speed(fix.header.sample_time_s, fix.speed_mps)
        if self.plane is None:
            self.origin = (fix.latitude_deg, fix.longitude_deg, fix.altitude_m)
            self.plane = LocalTangentPlane(*self.origin)
        self._learn_fix_interval(fix.header.sample_time_s)
        east_m, north_m, _ = self.plane.to_enu(fix.latitude_deg, fix.longitude_deg, fix.altitude_m)
        if math.hypot(east_m, north_m) > self.config.max_origin_distance_m:
            self.counters[InputEvent.FIX_FAR_FROM_ORIGIN] += 1
            if self.far_fix_distance_m is None:  # along the ellipsoid: the plane's distance shrinks far out
                self.far_fix_distance_m = float(vdist(self.origin[0], self.origin[1], fix.latitude_deg,
                                                      fix.longitude_deg)[0])
            return None
        # Producers older than velocity_valid (the simulator's gnss/fix) leave it false but fill the speed.
        velocity_valid = fix.velocity_valid or fix.speed_mps > 0.0
        heading_rad = _enu_heading_rad(fix.heading_deg) if fix.heading_valid else None
        # A fix's time is known only to the spread of its latency: it is off along the track by up to speed
        # times that, which its noise must allow for (else a 1 cm RTK fix late by 4 ms at 80 km/h is refused).
        timing_std_m = fix.speed_mps * self.config.gnss_time_jitter_s
        event = _Fix(east_m, north_m, math.hypot(stds[0], timing_std_m), math.hypot(stds[1], timing_std_m),
                     fix.fix_mode, fix.speed_mps, fix.course_deg, velocity_valid, heading_rad)
        return self._add(fix.header.sample_time_s, event)

    def _learn_fix_interval(self, time_s: float) -> None:
        if self._last_fix_input_s is None or time_s > self._last_fix_input_s:
            if self._last_fix_input_s is not None:
                step_s = time_s - self._last_fix_input_s
                self._fix_interval_s = step_s if self._fix_interval_s is None else min(self._fix_interval_s, step_s)
            interval_s = self._fix_interval_s if self._fix_interval_s is not None else ASSUMED_FIX_INTERVAL_S
            timeout_s = max(self.config.gnss_timeout_s, FIX_INTERVALS_FRESH * interval_s)
            self.thresholds = replace(self.thresholds, gnss_timeout_s=timeout_s)
        self._last_fix_input_s = time_s

    def on_can_state(self, msg: vehicle_pb2.VehicleCanState) -> Insertion | None:
        try:
            sample = self.odometry.sample(msg)
        except ValueError:
            self.counters[InputEvent.ODOMETRY_INVALID] += 1
            return None
        return self._add(sample.time_s, sample)

    def on_imu(self, msg: vehicle_pb2.ImuSample) -> Insertion | None:
        # A car that reports no longitudinal acceleration sends NaN there: its yaw rate is still good.
        if not math.isfinite(msg.yaw_rate_radps) or math.isinf(msg.accel_longitudinal_mps2):
            self.counters[InputEvent.IMU_INVALID] += 1
            return None
        return self._add(msg.header.sample_time_s, _Imu(msg.yaw_rate_radps, msg.accel_longitudinal_mps2))

    def _add(self, time_s: float, event: object) -> Insertion:
        latest_s = self._buffer.latest_time_s
        if not self.config.compensate_latency and latest_s is not None:
            time_s = max(time_s, latest_s)
        insertion = self._buffer.add(time_s, event)
        if insertion is Insertion.TOO_OLD:
            self.counters[InputEvent.TOO_OLD] += 1
        return insertion

    # --- fusion (called by the replay buffer, in time order) ------------------------------------
    def _snapshot(self) -> tuple:
        return self.ekf.snapshot(), self._book

    def _restore(self, snap: tuple) -> None:
        ekf_snap, self._book = snap
        self.ekf.restore(ekf_snap)

    def _apply(self, time_s: float, event: object) -> None:
        if isinstance(event, _Fix):
            self._apply_fix(time_s, event)
        elif isinstance(event, OdometrySample):
            self._apply_odometry(time_s, event)
        else:
            self._apply_imu(time_s, event)

    def _apply_fix(self, time_s: float, fix: _Fix) -> None:
        if (not self.ekf.initialised or not self._book.heading_known) and self._try_initialise(time_s, fix):
            return
        self.ekf.predict_to(time_s)
        book = self._book
        # Without a heading the state is the antenna itself (see _initialise): a lever arm would let position
        # noise pass for a heading.
        lever_arm = self.lever_arm if book.heading_known else NO_LEVER_ARM
        if self.ekf.update_gnss_position(fix.east_m, fix.north_m, fix.std_east_m, fix.std_north_m, lever_arm):
            self.counters[InputEvent.FIX_FUSED] += 1
            self._book = _replace(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, gated=None,
                                  fused_fix_std_m=_fix_std_m(fix))
        else:
            self._gated_fix(time_s, fix)
        self._fuse_gnss_motion(time_s, fix)

    def _gated_fix(self, time_s: float, fix: _Fix) -> None:
        book, config = self._book, self.config
        self.counters[InputEvent.FIX_GATED] += 1
        x, y = self.lever_arm.rear_axle_position(fix.east_m, fix.north_m, self.ekf.x[HEADING])
        offset_m = (x - float(self.ekf.x[E]), y - float(self.ekf.x[N]))
        fix_std_m = _fix_std_m(fix)
        # Only an RTK solution is precise enough to tell a multipath step from its own noise.
        floor_m = config.gnss_reset_consistency_m if fix.fix_mode in RTK_FIX_MODES else math.inf
        gated = GatedFixes(time_s, offset_m) if book.gated is None else book.gated.with_fix(
            time_s, offset_m, fix_std_m, floor_m)
        refused_s = time_s - gated.since_s
        if refused_s >= config.gnss_reset_after_s and (
                refused_s >= config.gnss_reset_unexplained_after_s or self._could_have_drifted(offset_m)):
            # The GNSS has disagreed for long, and smoothly: trust it over a filter that has drifted.
            self.ekf.reset_position(x, y, fix_std_m)
            self.counters[InputEvent.GNSS_RESET] += 1
            self._book = _replace(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, gated=None,
                                  fused_fix_std_m=fix_std_m)
        else:
            self._book = _replace(book, gated=gated)

    def _could_have_drifted(self, offset_m: tuple[float, float]) -> bool:
        """Whether the estimate can be this far off: by its own uncertainty, or by the error of the fixes it
        followed last (a DGPS solution's bias, which the next RTK fix shows as a step)."""
        std_m = max(_position_std_m(self.ekf.P), self._book.fused_fix_std_m)
        return math.hypot(*offset_m) <= self.config.gnss_reset_sigmas * std_m

    def _fuse_gnss_motion(self, time_s: float, fix: _Fix) -> None:
        """The receiver's heading, and without odometry its speed and course (a receiver alone)."""
        config, book = self.config, self._book
        if fix.heading_rad is not None:
            self.ekf.update_heading(fix.heading_rad, math.radians(config.gnss_heading_std_deg))
        odometry_s = book.last_odometry_time_s
        if not fix.velocity_valid or (odometry_s is not None and time_s - odometry_s <= config.odometry_timeout_s):
            return
        self.ekf.update_speed(fix.speed_mps, config.gnss_speed_std_mps, UpdateKind.GNSS_SPEED, soft=True)
        if fix.heading_rad is None and fix.speed_mps >= config.min_course_speed_mps:
            self.ekf.update_heading(_enu_heading_rad(fix.course_deg), math.radians(config.gnss_course_std_deg),
                                    soft=True)

    def _initial_heading(self, time_s: float, fix: _Fix) -> tuple[float, float, float | None] | None:
        """(heading, its std, speed along the track or None) when this fix tells the heading, else None."""
        book, config = self._book, self.config
        if fix.heading_rad is not None:
            return fix.heading_rad, math.radians(config.gnss_heading_std_deg), None
        if fix.velocity_valid and fix.speed_mps >= config.min_course_speed_mps:
            return _enu_heading_rad(fix.course_deg), config.initial_heading_std_rad, None
        if book.pending_fix is not None and not fix.velocity_valid:  # a receiver's own slow speed beats a track
            previous_time_s, previous = book.pending_fix
            de, dn = fix.east_m - previous.east_m, fix.north_m - previous.north_m
            # A track shorter than the fixes' own noise says nothing about the heading.
            min_track_m = max(HEADING_FROM_TRACK_MIN_M, 3.0 * max(fix.std_east_m, fix.std_north_m))
            if math.hypot(de, dn) >= min_track_m and time_s > previous_time_s:
                return math.atan2(dn, de), config.initial_heading_std_rad, math.hypot(de, dn) / (time_s - previous_time_s)
        if book.last_speed_mps is not None and abs(book.last_speed_mps) < STATIONARY_SPEED_MPS:
            return 0.0, UNKNOWN_HEADING_STD_RAD, None  # the wheels say standing: any heading will do for now
        return None

    def _try_initialise(self, time_s: float, fix: _Fix) -> bool:
        """(Re)initialises the filter from this fix when it tells the heading, or at the first fix with the
        heading unknown (a position as soon as there is a fix). False: fuse the fix as usual."""
        book = self._book
        found = self._initial_heading(time_s, fix)
        if found is None:
            # Keep the oldest fix as the start of the track, unless it is too old to tell the heading.
            if book.pending_fix is None or time_s - book.pending_fix[0] > PENDING_FIX_MAX_AGE_S:
                self._book = book = _replace(book, pending_fix=(time_s, fix))
            if self.ekf.initialised:
                return False
            self._initialise(time_s, fix, None, UNKNOWN_HEADING_STD_RAD, None)
            self._book = _replace(self._book, pending_fix=book.pending_fix, heading_known=False)
            return True
        heading_rad, heading_std_rad, track_speed_mps = found
        self._initialise(time_s, fix, heading_rad, heading_std_rad, track_speed_mps)
        return True

    def _initialise(self, time_s: float, fix: _Fix, heading_rad: float | None, heading_std_rad: float,
                    track_speed_mps: float | None) -> None:
        book = self._book
        speed_mps, speed_std = (fix.speed_mps if fix.velocity_valid else 0.0), self.config.initial_speed_std_mps
        if book.last_speed_mps is not None:
            speed_mps, speed_std = book.last_speed_mps, self.odometry.speed_std_mps
        elif track_speed_mps is not None:
            speed_mps = track_speed_mps
        elif fix.velocity_valid:
            speed_std = self.config.gnss_speed_std_mps
        x0 = np.zeros(STATE_DIM)
        arm_m = math.hypot(self.lever_arm.x_m, self.lever_arm.y_m)
        if heading_rad is None:
            # Heading unknown: the rear axle is somewhere on a circle around the antenna, whose centre is
            # the best guess (variance arm^2 / 2 along each axis).
            x0[E], x0[N] = fix.east_m, fix.north_m
            arm_var = arm_m**2 / 2.0
        else:
            x0[E], x0[N] = self.lever_arm.rear_axle_position(fix.east_m, fix.north_m, heading_rad)
            x0[HEADING] = heading_rad
            arm_var = (arm_m * heading_std_rad) ** 2
        x0[SPEED] = speed_mps
        P0 = np.diag([fix.std_east_m**2 + arm_var, fix.std_north_m**2 + arm_var, heading_std_rad**2, speed_std**2,
                      INITIAL_YAW_RATE_STD_RADPS**2, INITIAL_ACCEL_STD_MPS2**2,
                      self.config.imu_yaw_rate_bias_std_radps**2, self.config.imu_accel_bias_std_mps2**2])
        self.ekf.initialise(time_s, x0, P0)
        self.counters[InputEvent.FIX_FUSED] += 1
        self._book = _replace(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, pending_fix=None,
                              heading_known=heading_rad is not None, gated=None, fused_fix_std_m=_fix_std_m(fix))

    def _apply_odometry(self, time_s: float, sample: OdometrySample) -> None:
        self._book = _replace(self._book, last_speed_mps=sample.speed_mps, last_odometry_time_s=time_s)
        if sample.yaw_rate_radps is not None:
            self._book = _replace(self._book, last_yaw_rate_radps=sample.yaw_rate_radps)
        if not self.ekf.initialised:
            self.ekf.hold_steering(sample.steering_angle_rad)
            return
        self.ekf.predict_to(time_s)  # under the steering held since the previous sample
        self.ekf.hold_steering(sample.steering_angle_rad)
        if abs(sample.speed_mps) < STANDSTILL_SPEED_MPS:
            self.counters[InputEvent.STANDSTILL] += 1
            self.ekf.zero_velocity_update()
            return
        if self._steered or sample.yaw_rate_radps is None:
            self.ekf.update_speed(sample.speed_mps, sample.speed_std_mps)
        else:
            accepted = self.ekf.update_odometry(sample.speed_mps, sample.yaw_rate_radps, sample.speed_std_mps,
                                                sample.yaw_rate_std_radps)
            self._watch_yaw_rate(time_s, accepted, sample.yaw_rate_radps, sample.yaw_rate_std_radps, by_imu=False)

    def _apply_imu(self, time_s: float, imu: _Imu) -> None:
        self._book = _replace(self._book, last_yaw_rate_radps=imu.yaw_rate_radps)
        if not self.ekf.initialised:
            return
        self.ekf.predict_to(time_s)
        if not self._steered:
            std_radps = self.config.imu_yaw_rate_std_radps
            accepted = self.ekf.update_yaw_rate(imu.yaw_rate_radps, std_radps)
            self._watch_yaw_rate(time_s, accepted, imu.yaw_rate_radps, std_radps, by_imu=True)
        if self.config.use_imu_accel and math.isfinite(imu.accel_mps2):
            self.ekf.update_accel(imu.accel_mps2, self.config.imu_accel_std_mps2)

    def _watch_yaw_rate(self, time_s: float, accepted: bool, measured_radps: float, std_radps: float,
                        by_imu: bool) -> None:
        since_s = self._book.yaw_rate_refused_since_s
        if accepted:
            if since_s is not None:
                self._book = _replace(self._book, yaw_rate_refused_since_s=None)
            return
        if since_s is None:
            self._book = _replace(self._book, yaw_rate_refused_since_s=time_s)
        elif time_s - since_s >= self.config.yaw_rate_reset_after_s:
            self.ekf.reset_yaw_rate(measured_radps, std_radps, time_s - since_s, by_imu)
            self.counters[InputEvent.YAW_RATE_RESET] += 1
            self._book = _replace(self._book, yaw_rate_refused_since_s=None)

    # --- output --------------------------------------------------------------------------------
    @property
    def last_fix_mode(self) -> int:
        return self._book.last_fix_mode

    def stats(self) -> dict[str, int]:
        """Counters for diagnostics: inputs by outcome, gated and accepted updates, replays."""
        counts = {f"input_{event.value}": n for event, n in self.counters.items()}
        counts.update(self.ekf.update_counts())
        counts.update({f"insertion_{kind.value}": n for kind, n in self._buffer.counts.items()})
        counts["replayed_events"] = self._buffer.replayed_events
        counts.update(self.odometry.stats())
        return counts

    def estimate(self, time_s: float) -> ego_pb2.EgoState:
        """The ego state predicted to time_s (the filter itself is not moved)."""
        self._sequence += 1
        state = ego_pb2.EgoState()
        state.header.sample_time_s = time_s
        state.header.vehicle_id = self.config.vehicle_id
        state.header.sender = SENDER
        state.header.sequence = self._sequence
        state.last_fix_mode = self._book.last_fix_mode
        if not self.ekf.initialised:
            return self._without_position(state)
        x, P = self.ekf.predicted(time_s)
        state.x_m, state.y_m, state.heading_rad = x[E], x[N], x[HEADING]
        state.speed_mps, state.yaw_rate_radps, state.accel_mps2 = x[SPEED], x[YAW_RATE], x[ACCEL]
        state.covariance.extend(P[:VEHICLE_STATE_DIM, :VEHICLE_STATE_DIM].ravel().tolist())
        position_std_m = _position_std_m(P)
        state.position_std_m = position_std_m
        since_fix_s = None if self._book.last_fix_time_s is None else time_s - self._book.last_fix_time_s
        state.mode = localisation_mode(True, position_std_m, since_fix_s, self._book.last_fix_mode, self.thresholds,
                                       heading_known=self._book.heading_known)
        state.latitude_deg, state.longitude_deg, _ = self.plane.to_geodetic(float(x[E]), float(x[N]))
        if self.road_map is not None:
            match = self.road_map.match(x[E], x[N], x[HEADING])
            if match is not None:
                lane = state.lane
                lane.matched = True
                lane.lane_index = match.lane_index
                lane.lane_id = match.lane.lane_id
                lane.road_id = match.lane.road_id
                lane.station_m = match.station_m
                lane.lateral_offset_m = match.lateral_offset_m
                lane.heading_error_rad = match.heading_error_rad
                lane.lane_width_m = match.lane.width_m
                lane.curvature_1pm = match.curvature_1pm
        return state

    def _without_position(self, state: ego_pb2.EgoState) -> ego_pb2.EgoState:
        """No fix yet: no position (LOST, no covariance: x, y and heading mean nothing), but the car's own
        latest speed and yaw rate, which need no fix. (position_std_m stays 0, not infinite: consumers that
        ignore the mode would turn an infinite one into NaN covariances.)"""
        state.mode = ego_pb2.LOCALISATION_MODE_LOST
        if self._book.last_speed_mps is not None or self._book.last_yaw_rate_radps is not None:
            state.speed_mps = self._book.last_speed_mps or 0.0
            state.yaw_rate_radps = self._book.last_yaw_rate_radps or 0.0
        return state


def _fix_std_m(fix: _Fix) -> float:
    return max(fix.std_east_m, fix.std_north_m)


def _position_std_m(P: np.ndarray) -> float:
    """The position's std along its worst direction."""
    return math.sqrt(max(float(np.linalg.eigvalsh(P[:2, :2])[-1]), 0.0))


def _enu_heading_rad(course_deg: float) -> float:
    """NMEA course or heading (from north, clockwise, degrees) -> ENU heading (from east, anticlockwise)."""
    return math.pi / 2.0 - math.radians(course_deg)


def _replace(book: _Bookkeeping, **changes) -> _Bookkeeping:
    return _Bookkeeping(**{**book.__dict__, **changes})
