"""Geolocator: GNSS fixes, CAN odometry and IMU samples in, EgoState at the rear axle out.

Fed by method calls carrying their sample times; deterministic (no clock, no randomness). Each input is
fused at its own sample time through a replay buffer (latency.py), so a late GNSS fix acts where the
vehicle was when it was measured. The ego state is then matched to the lane map.
"""

from __future__ import annotations

import enum
import math
from collections import Counter
from dataclasses import replace

import numpy as np
from pymap3d.vincenty import vdist

from coopdrive.can.adapter import MountPoint, OdometryOptions
from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap import RoadMap
from coopdrive.services.geolocation.bookkeeping import Bookkeeping, Fix, Imu, replaced
from coopdrive.services.geolocation.config import GeolocatorConfig
from coopdrive.services.geolocation.ego_output import EgoOutput, position_std_m_of
from coopdrive.vehicle import PASSENGER_CAR, VehicleDescription
from coopdrive.services.geolocation.ekf import GeolocationEkf, UpdateKind, gnss_position_std_m
from coopdrive.services.geolocation.gated_fixes import GatedFixes
from coopdrive.services.geolocation.initial_heading import UNKNOWN_HEADING_STD_RAD, enu_heading_rad, initial_heading
from coopdrive.services.geolocation.frames import RTK_FIX_MODES, LeverArm, ModeThresholds
from coopdrive.services.geolocation.latency import Insertion, ReplayBuffer
from coopdrive.services.geolocation.nuisances import estimated_nuisances
from coopdrive.services.geolocation.motion_models import (
    GNSS_ERROR_E, GNSS_ERROR_N, GNSS_TIME_ERROR, HEADING, SPEED, STATE_DIM, CtraModel, E, KinematicBicycleModel,
    MotionModelKind, N,
)
from coopdrive.services.geolocation.odometry import Odometry, OdometrySample
from coopdrive.v1 import ego_pb2, gnss_pb2, vehicle_pb2

# Rear wheels this slow are standing still (wheel-speed sensors read zero there, give or take their noise).
STANDSTILL_SPEED_MPS = 0.05
PENDING_FIX_MAX_AGE_S = 5.0
INITIAL_YAW_RATE_STD_RADPS = 0.1
INITIAL_ACCEL_STD_MPS2 = 1.0
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


# The events counted as the filter applies an input: an input fused again after a late one (latency.py) must not
# count twice, so these counts go back with the filter's state. The others are counted once, as inputs arrive.
APPLIED_EVENTS = (InputEvent.FIX_FUSED, InputEvent.FIX_GATED, InputEvent.GNSS_RESET, InputEvent.YAW_RATE_RESET,
                  InputEvent.STANDSTILL)


class Geolocator:
    def __init__(self, config: GeolocatorConfig, road_map: RoadMap | None = None,
                 origin: tuple[float, float, float] | None = None, first_fix_origin: bool = False,
                 vehicle: VehicleDescription = PASSENGER_CAR, antenna: MountPoint | None = None) -> None:
        """The local frame's origin: the road map's, else origin, else (first_fix_origin) the first fix's. vehicle:
        the geometry the config leaves open; antenna: where the car's file puts it, when the config does not."""
        config = self.config = config.of_vehicle(vehicle, antenna)
        self._fix_std_by_mode_m = config.gnss_fix_std_m.by_mode()
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
        noise = config.process_noise()
        # The bicycle model turns by the steering angle: its yaw rate is not measured but follows the wheels.
        self._steered = config.motion_model is MotionModelKind.KINEMATIC_BICYCLE
        model = KinematicBicycleModel(noise, config.wheelbase_m) if self._steered else CtraModel(noise)
        self.ekf = GeolocationEkf(model, config.gate_probability, config.gnss_error_by_fix_mode)
        self.odometry = Odometry(config.track_width_m, config.wheel_speed_std_mps)
        self.lever_arm = LeverArm(config.antenna_x_m, config.antenna_y_m)
        self.thresholds = ModeThresholds(config.precise_std_m, config.lost_std_m, config.gnss_timeout_s)
        self.counters: Counter[InputEvent] = Counter()
        self._book = Bookkeeping()
        self._buffer = ReplayBuffer(self._apply, self._snapshot, self._restore, config.history_s)
        self._output = EgoOutput(config)

    def configure_odometry(self, options: OdometryOptions) -> None:
        """How this car's wheels are read (its vehicle CAN adapter's odometry options)."""
        self.odometry = Odometry(self.config.track_width_m, self.config.wheel_speed_std_mps, options)

    # --- inputs --------------------------------------------------------------------------------
    def on_gnss_fix(self, fix: gnss_pb2.GnssFix) -> Insertion | None:
        """A fix, fused at fix.header.sample_time_s. Returns how it was inserted, None if not usable."""
        stds = gnss_position_std_m(fix.fix_mode, fix.std_east_m, fix.std_north_m, self._fix_std_by_mode_m)
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
        heading_rad = enu_heading_rad(fix.heading_deg) if fix.heading_valid else None
        # Its stamp's spread is a noise along the track (else a 1 cm RTK fix 4 ms late at 80 km/h is refused).
        event = Fix(east_m, north_m, stds[0], stds[1], fix.fix_mode, fix.speed_mps, fix.course_deg, velocity_valid,
                    heading_rad, self.config.gnss_time_jitter_s)
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
        return self._add(msg.header.sample_time_s, Imu(msg.yaw_rate_radps, msg.accel_longitudinal_mps2))

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
        return self.ekf.snapshot(), self._book, {event: self.counters[event] for event in APPLIED_EVENTS}

    def _restore(self, snap: tuple) -> None:
        ekf_snap, self._book, applied = snap
        self.ekf.restore(ekf_snap)
        for event, count in applied.items():
            self.counters[event] = count
        self.counters += Counter()  # drops the zeros: an event that never happened is not listed

    def _apply(self, time_s: float, event: object) -> None:
        if isinstance(event, Fix):
            self._apply_fix(time_s, event)
        elif isinstance(event, OdometrySample):
            self._apply_odometry(time_s, event)
        else:
            self._apply_imu(time_s, event)

    def _apply_fix(self, time_s: float, fix: Fix) -> None:
        if (not self.ekf.initialised or not self._book.heading_known) and self._try_initialise(time_s, fix):
            return
        self.ekf.predict_to(time_s)
        book = self._book
        # Without a heading the state is the antenna itself (see _initialise): a lever arm would let position
        # noise pass for a heading.
        lever_arm = self.lever_arm if book.heading_known else NO_LEVER_ARM
        if self.ekf.update_gnss_position(fix.east_m, fix.north_m, fix.std_east_m, fix.std_north_m, lever_arm,
                                         fix.time_jitter_s, new_mode=fix.fix_mode != book.last_fix_mode):
            self.counters[InputEvent.FIX_FUSED] += 1
            self._book = replaced(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, gated=None,
                                  fused_fix_std_m=_fix_std_m(fix))
        else:
            self._gated_fix(time_s, fix)
        self._fuse_gnss_motion(time_s, fix)

    def _gated_fix(self, time_s: float, fix: Fix) -> None:
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
            self._book = replaced(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, gated=None,
                                  fused_fix_std_m=fix_std_m)
        else:
            self._book = replaced(book, gated=gated)

    def _could_have_drifted(self, offset_m: tuple[float, float]) -> bool:
        """Whether the estimate can be this far off: by its own uncertainty, or by the error of the fixes it
        followed last (a DGPS solution's bias, which the next RTK fix shows as a step)."""
        std_m = max(position_std_m_of(self.ekf.P), self._book.fused_fix_std_m)
        return math.hypot(*offset_m) <= self.config.gnss_reset_sigmas * std_m

    def _fuse_gnss_motion(self, time_s: float, fix: Fix) -> None:
        """The receiver's heading, and without odometry its speed and course (a receiver alone)."""
        config, book = self.config, self._book
        if fix.heading_rad is not None:
            self.ekf.update_heading(fix.heading_rad, math.radians(config.gnss_heading_std_deg))
        odometry_s = book.last_odometry_time_s
        if not fix.velocity_valid:
            return
        course_usable = fix.heading_rad is None and fix.speed_mps >= config.min_course_speed_mps and book.heading_known
        if odometry_s is not None and time_s - odometry_s <= config.odometry_timeout_s:
            if config.course_with_odometry and course_usable:
                self.ekf.update_course(enu_heading_rad(fix.course_deg), math.radians(config.gnss_course_std_deg),
                                       self.lever_arm)
            return
        self.ekf.update_speed(fix.speed_mps, config.gnss_speed_std_mps, UpdateKind.GNSS_SPEED, soft=True)
        if fix.heading_rad is None and fix.speed_mps >= config.min_course_speed_mps:
            self.ekf.update_course(enu_heading_rad(fix.course_deg), math.radians(config.gnss_course_std_deg),
                                   self.lever_arm if book.heading_known else NO_LEVER_ARM, soft=True)

    def _try_initialise(self, time_s: float, fix: Fix) -> bool:
        """(Re)initialises the filter from this fix when it tells the heading, or at the first fix with the
        heading unknown (a position as soon as there is a fix). False: fuse the fix as usual."""
        book = self._book
        found = initial_heading(time_s, fix, book, self.config)
        if found is None:
            # Keep the oldest fix as the start of the track, unless it is too old to tell the heading.
            if book.pending_fix is None or time_s - book.pending_fix[0] > PENDING_FIX_MAX_AGE_S:
                self._book = book = replaced(book, pending_fix=(time_s, fix))
            if self.ekf.initialised:
                return False
            self._initialise(time_s, fix, None, UNKNOWN_HEADING_STD_RAD, None)
            self._book = replaced(self._book, pending_fix=book.pending_fix, heading_known=False)
            return True
        heading_rad, heading_std_rad, track_speed_mps = found
        self._initialise(time_s, fix, heading_rad, heading_std_rad, track_speed_mps)
        return True

    def _initialise(self, time_s: float, fix: Fix, heading_rad: float | None, heading_std_rad: float,
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
        error_var = self.config.gnss_error_std_m**2
        P0 = np.diag([fix.std_east_m**2 + arm_var + error_var, fix.std_north_m**2 + arm_var + error_var,
                      heading_std_rad**2, speed_std**2, INITIAL_YAW_RATE_STD_RADPS**2, INITIAL_ACCEL_STD_MPS2**2,
                      self.config.imu_yaw_rate_bias_std_radps**2, self.config.imu_accel_bias_std_mps2**2,
                      error_var, error_var, self.config.gnss_time_error_std_s**2])
        # The position is the fix less its correlated error (estimated 0): off by just what that error is.
        P0[E, GNSS_ERROR_E] = P0[GNSS_ERROR_E, E] = P0[N, GNSS_ERROR_N] = P0[GNSS_ERROR_N, N] = -error_var
        _add_stamp_error(P0, speed_mps, heading_rad, self.config.gnss_time_error_std_s, fix.time_jitter_s)
        self.ekf.initialise(time_s, x0, P0)
        self.counters[InputEvent.FIX_FUSED] += 1
        self._book = replaced(book, last_fix_time_s=time_s, last_fix_mode=fix.fix_mode, pending_fix=None,
                              heading_known=heading_rad is not None, gated=None, fused_fix_std_m=_fix_std_m(fix))

    def _apply_odometry(self, time_s: float, sample: OdometrySample) -> None:
        self._book = replaced(self._book, last_speed_mps=sample.speed_mps, last_odometry_time_s=time_s)
        if sample.yaw_rate_radps is not None:
            self._book = replaced(self._book, last_yaw_rate_radps=sample.yaw_rate_radps)
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

    def _apply_imu(self, time_s: float, imu: Imu) -> None:
        self._book = replaced(self._book, last_yaw_rate_radps=imu.yaw_rate_radps)
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
                self._book = replaced(self._book, yaw_rate_refused_since_s=None)
            return
        if since_s is None:
            self._book = replaced(self._book, yaw_rate_refused_since_s=time_s)
        elif time_s - since_s >= self.config.yaw_rate_reset_after_s:
            self.ekf.reset_yaw_rate(measured_radps, std_radps, time_s - since_s, by_imu)
            self.counters[InputEvent.YAW_RATE_RESET] += 1
            self._book = replaced(self._book, yaw_rate_refused_since_s=None)

    # --- output --------------------------------------------------------------------------------
    @property
    def last_fix_mode(self) -> int:
        return self._book.last_fix_mode

    def stats(self) -> dict[str, float]:
        """Counters for diagnostics: inputs by outcome, gated and accepted updates, replays, estimated nuisances."""
        counts = {f"input_{event.value}": n for event, n in self.counters.items()}
        counts.update(self.ekf.update_counts())
        counts.update({f"insertion_{kind.value}": n for kind, n in self._buffer.counts.items()})
        counts["replayed_events"] = self._buffer.replayed_events
        counts.update(self.odometry.stats())
        counts.update(estimated_nuisances(self.ekf, self.config.gnss_time_error_std_s, self.odometry.wheel_scale))
        return counts

    def estimate(self, time_s: float) -> ego_pb2.EgoState:
        """The ego state predicted to time_s (the filter itself is not moved)."""
        return self._output.estimate(time_s, self.ekf, self._book, self.plane, self.road_map, self.thresholds)


def _add_stamp_error(P0: np.ndarray, speed_mps: float, heading_rad: float | None, time_error_std_s: float,
                     jitter_s: float) -> None:
    """The first fix's time stamp is off too: the position taken from it is the antenna's speed times that error
    behind or ahead (correlated with the time error state, which the next fixes share: else they would learn the
    first fix's own stamp error as everyone's). Heading unknown: as far either way, along both axes."""
    along_m = abs(speed_mps) * math.hypot(time_error_std_s, jitter_s)
    if heading_rad is None:
        P0[E, E] += along_m**2
        P0[N, N] += along_m**2
        return
    along = np.array([math.cos(heading_rad), math.sin(heading_rad)])
    P0[E:N + 1, E:N + 1] += along_m**2 * np.outer(along, along)
    # The position is the fix plus speed times the time error (a fix stamped late shows where the car was).
    P0[[E, N], GNSS_TIME_ERROR] = P0[GNSS_TIME_ERROR, [E, N]] = speed_mps * time_error_std_s**2 * along


def _fix_std_m(fix: Fix) -> float:
    return max(fix.std_east_m, fix.std_north_m)
