"""Vehicle frames and the localisation mode.

The estimated reference point is the middle of the rear axle (where the kinematic bicycle model has no
side slip and where iCLCM rearAxleLocation is measured); the GNSS antenna sits at a lever arm from it,
in the vehicle frame (x forward, y left).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.v1 import ego_pb2, gnss_pb2

RTK_FIX_MODES = (gnss_pb2.FIX_MODE_RTK_FIXED, gnss_pb2.FIX_MODE_RTK_FLOAT)


@dataclass(frozen=True)
class LeverArm:
    """Antenna position relative to the rear-axle centre, vehicle frame, m."""

    x_m: float = 0.0
    y_m: float = 0.0

    def antenna_position(self, east_m: float, north_m: float, heading_rad: float) -> tuple[float, float]:
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return east_m + c * self.x_m - s * self.y_m, north_m + s * self.x_m + c * self.y_m

    def rear_axle_position(self, antenna_east_m: float, antenna_north_m: float,
                           heading_rad: float) -> tuple[float, float]:
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return antenna_east_m - (c * self.x_m - s * self.y_m), antenna_north_m - (s * self.x_m + c * self.y_m)

    def d_antenna_d_heading(self, heading_rad: float) -> tuple[float, float]:
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return -s * self.x_m - c * self.y_m, c * self.x_m - s * self.y_m


@dataclass(frozen=True)
class ModeThresholds:
    precise_std_m: float = 0.3  # lane-level control needs decimetres (Heudiasyc lateral error 0.29 m)
    lost_std_m: float = 5.0  # beyond this the lane is unknown
    gnss_timeout_s: float = 0.5  # no fused fix for this long: dead reckoning


def localisation_mode(initialised: bool, position_std_m: float, since_last_fix_s: float | None,
                      last_fix_mode: int, thresholds: ModeThresholds, heading_known: bool = True) -> int:
    """LocalisationMode from the fix mode of the last fused fix, its age and the position covariance.

    While fixes are being fused the position is known as well as the receiver says (a single-point fix's
    5 m is coarse, not lost); only without them does a growing uncertainty end in LOST. Without a heading
    (a receiver standing still, no dual antenna) the ego is never good enough for lane-level control."""
    if not initialised:
        return ego_pb2.LOCALISATION_MODE_LOST
    if since_last_fix_s is None or since_last_fix_s > thresholds.gnss_timeout_s:
        if position_std_m > thresholds.lost_std_m:
            return ego_pb2.LOCALISATION_MODE_LOST
        return ego_pb2.LOCALISATION_MODE_DEAD_RECKONING
    if position_std_m <= thresholds.precise_std_m and last_fix_mode in RTK_FIX_MODES and heading_known:
        return ego_pb2.LOCALISATION_MODE_GNSS_PRECISE
    return ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED
