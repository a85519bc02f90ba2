"""A synthetic drive (truth at the rear axle) and the sensor messages a car would produce on it, seeded."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pymap3d

from coopdrive.v1 import gnss_pb2, vehicle_pb2
from coopdrive.vehicle import PASSENGER_CAR

ORIGIN = (51.4715, 5.6010, 20.0)
# The car's, as the geolocator takes it where its config leaves the geometry open.
TRACK_WIDTH_M = PASSENGER_CAR.track_width_m
ODOMETRY_DT_S = 0.01
GNSS_EVERY = 5  # odometry steps per GNSS fix: 20 Hz


@dataclass
class Truth:
    time_s: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    heading_rad: np.ndarray
    speed_mps: np.ndarray
    yaw_rate_radps: np.ndarray


def drive(duration_s: float, speed_mps: float, curve_start_s: float | None, radius_m: float,
          ramp_s: float = 3.0, heading0_rad: float = 0.0) -> Truth:
    """Constant speed; yaw rate ramps from 0 to speed / radius (a left curve) from curve_start_s on."""
    n = int(round(duration_s / ODOMETRY_DT_S)) + 1
    t = np.arange(n) * ODOMETRY_DT_S
    if curve_start_s is None:
        yaw_rate = np.zeros(n)
    else:
        yaw_rate = speed_mps / radius_m * np.clip((t - curve_start_s) / ramp_s, 0.0, 1.0)
    heading = heading0_rad + np.concatenate(([0.0], np.cumsum(0.5 * (yaw_rate[1:] + yaw_rate[:-1]) * ODOMETRY_DT_S)))
    mid_heading = 0.5 * (heading[1:] + heading[:-1])
    x = np.concatenate(([0.0], np.cumsum(speed_mps * np.cos(mid_heading) * ODOMETRY_DT_S)))
    y = np.concatenate(([0.0], np.cumsum(speed_mps * np.sin(mid_heading) * ODOMETRY_DT_S)))
    return Truth(t, x, y, heading, np.full(n, speed_mps), yaw_rate)


def can_state(truth: Truth, i: int, rng: np.random.Generator, wheel_std_mps: float) -> vehicle_pb2.VehicleCanState:
    half_diff = 0.5 * truth.yaw_rate_radps[i] * TRACK_WIDTH_M
    msg = vehicle_pb2.VehicleCanState(
        wheel_speed_rear_left_mps=truth.speed_mps[i] - half_diff + rng.normal(0.0, wheel_std_mps),
        wheel_speed_rear_right_mps=truth.speed_mps[i] + half_diff + rng.normal(0.0, wheel_std_mps),
        gear=vehicle_pb2.GEAR_DRIVE)
    msg.header.sample_time_s = truth.time_s[i]
    return msg


def imu_sample(truth: Truth, i: int, rng: np.random.Generator, gyro_std_radps: float) -> vehicle_pb2.ImuSample:
    msg = vehicle_pb2.ImuSample(yaw_rate_radps=truth.yaw_rate_radps[i] + rng.normal(0.0, gyro_std_radps),
                                accel_longitudinal_mps2=rng.normal(0.0, 0.05))
    msg.header.sample_time_s = truth.time_s[i]
    return msg


def gnss_fix(truth: Truth, i: int, rng: np.random.Generator, std_m: float, lever_x_m: float,
             fix_mode: int = gnss_pb2.FIX_MODE_RTK_FIXED, offset_m: tuple[float, float] = (0.0, 0.0)
             ) -> tuple[gnss_pb2.GnssFix, float, float]:
    """The fix message and the noisy antenna position it carries (ENU) for computing raw errors."""
    heading = truth.heading_rad[i]
    east = truth.x_m[i] + lever_x_m * math.cos(heading) + rng.normal(0.0, std_m) + offset_m[0]
    north = truth.y_m[i] + lever_x_m * math.sin(heading) + rng.normal(0.0, std_m) + offset_m[1]
    lat, lon, alt = pymap3d.enu2geodetic(east, north, 0.0, *ORIGIN)
    fix = gnss_pb2.GnssFix(latitude_deg=float(lat), longitude_deg=float(lon), altitude_m=float(alt),
                           fix_mode=fix_mode, std_east_m=std_m, std_north_m=std_m, speed_mps=truth.speed_mps[i],
                           course_deg=math.degrees(math.pi / 2.0 - heading) % 360.0, satellites=12, hdop=0.8)
    fix.header.sample_time_s = truth.time_s[i]
    return fix, east - lever_x_m * math.cos(heading), north - lever_x_m * math.sin(heading)


@dataclass
class Run:
    time_s: np.ndarray
    error_xy_m: np.ndarray  # estimate - truth, at the estimate times
    position_cov: np.ndarray  # 2x2 per estimate
    heading_error_rad: np.ndarray
    modes: list
    raw_fix_error_m: np.ndarray  # antenna fix (lever arm removed) - truth, per fix sent
    fix_time_s: np.ndarray
    states: list


def simulate(geolocator, truth: Truth, seed: int, gnss_std_m: float, lever_x_m: float, wheel_std_mps: float = 0.01,
             outage_s: tuple[float, float] | None = None, fix_delay_s: float = 0.0,
             jump_at_s: float | None = None, jump_m: tuple[float, float] = (0.0, 0.0), jump_duration_s: float = 0.01,
             imu_gyro_std_radps=None,
             estimate_every: int = 10, steering_wheelbase_m: float | None = None,
             fix_mode: int = gnss_pb2.FIX_MODE_RTK_FIXED, mode_change: tuple[float, int, float] | None = None) -> Run:
    """Feed the geolocator like the bus would: odometry at 100 Hz, fixes at 20 Hz arriving fix_delay_s late.
    mode_change: (time_s, fix mode, std_m) of the fixes from then on."""
    rng = np.random.default_rng(seed)
    pending: list[tuple[float, gnss_pb2.GnssFix]] = []
    times, errors, covs, heading_errors, modes, raw, fix_times, states = [], [], [], [], [], [], [], []
    for i, t in enumerate(truth.time_s):
        msg = can_state(truth, i, rng, wheel_std_mps)
        if steering_wheelbase_m is not None:
            msg.steering_angle_rad = math.atan(truth.yaw_rate_radps[i] * steering_wheelbase_m / truth.speed_mps[i])
        geolocator.on_can_state(msg)
        if imu_gyro_std_radps is not None:
            geolocator.on_imu(imu_sample(truth, i, rng, imu_gyro_std_radps))
        in_outage = outage_s is not None and outage_s[0] <= t < outage_s[1]
        if i % GNSS_EVERY == 0 and not in_outage:
            jumped = jump_at_s is not None and jump_at_s - 1e-6 <= t < jump_at_s + jump_duration_s
            offset = jump_m if jumped else (0.0, 0.0)
            mode, std_m = fix_mode, gnss_std_m
            if mode_change is not None and t >= mode_change[0] - 1e-6:
                mode, std_m = mode_change[1:]
            fix, east, north = gnss_fix(truth, i, rng, std_m, lever_x_m, mode, offset_m=offset)
            pending.append((t + fix_delay_s, fix))
            raw.append(math.hypot(east - truth.x_m[i], north - truth.y_m[i]))
            fix_times.append(t)
        while pending and pending[0][0] <= t + 1e-9:
            geolocator.on_gnss_fix(pending.pop(0)[1])
        if i % estimate_every == 0:
            state = geolocator.estimate(t)
            if state.mode == 4:  # LOST before the first fix
                continue
            times.append(t)
            errors.append((state.x_m - truth.x_m[i], state.y_m - truth.y_m[i]))
            covs.append(np.array(state.covariance).reshape(6, 6)[:2, :2])
            heading_errors.append(math.remainder(state.heading_rad - truth.heading_rad[i], 2 * math.pi))
            modes.append(state.mode)
            states.append(state)
    return Run(np.array(times), np.array(errors), np.array(covs), np.array(heading_errors), modes, np.array(raw),
               np.array(fix_times), states)


def rmse_m(errors_xy: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.sum(errors_xy**2, axis=1))))
