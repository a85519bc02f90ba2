"""What the geolocator keeps between its inputs besides the filter: the GNSS fix and IMU sample as it fuses them,
and its bookkeeping (last fix, pending fix, last speed, whether the heading is known, ...), replaced as a whole so a
replay can restore it."""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.services.geolocation.gated_fixes import GatedFixes
from coopdrive.v1 import gnss_pb2


@dataclass(frozen=True)
class Fix:
    east_m: float
    north_m: float
    std_east_m: float
    std_north_m: float
    fix_mode: int
    speed_mps: float
    course_deg: float
    velocity_valid: bool = False
    heading_rad: float | None = None  # dual-antenna heading, ENU
    time_jitter_s: float = 0.0  # the white spread of the fix's time stamp (geolocator.gnss_time_jitter_s)


@dataclass(frozen=True)
class Imu:
    yaw_rate_radps: float
    accel_mps2: float


@dataclass(frozen=True)
class Bookkeeping:
    last_fix_time_s: float | None = None
    last_fix_mode: int = gnss_pb2.FIX_MODE_UNSPECIFIED
    # The fixes refused since the last fused one (None while fixes are fused).
    gated: GatedFixes | None = None
    pending_fix: tuple[float, Fix] | None = None
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


def replaced(book: Bookkeeping, **changes) -> Bookkeeping:
    return Bookkeeping(**{**book.__dict__, **changes})
