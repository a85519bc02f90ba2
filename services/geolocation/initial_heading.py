"""What a GNSS fix tells of the car's heading when the geolocator (re)initialises its filter: the receiver's own
heading (dual antenna), its course over ground when fast enough, the track from an earlier fix, or any heading
when the wheels say the car stands."""

from __future__ import annotations

import math

from coopdrive.services.geolocation.bookkeeping import Bookkeeping, Fix
from coopdrive.services.geolocation.config import GeolocatorConfig

STATIONARY_SPEED_MPS = 0.5
HEADING_FROM_TRACK_MIN_M = 2.0  # two fixes this far apart give a usable heading
UNKNOWN_HEADING_STD_RAD = math.pi


def initial_heading(time_s: float, fix: Fix, book: Bookkeeping, config: GeolocatorConfig
                    ) -> tuple[float, float, float | None] | None:
    """(heading, its std, speed along the track or None) when this fix tells the heading, else None."""
    if fix.heading_rad is not None:
        return fix.heading_rad, math.radians(config.gnss_heading_std_deg), None
    if fix.velocity_valid and fix.speed_mps >= config.min_course_speed_mps:
        return enu_heading_rad(fix.course_deg), config.initial_heading_std_rad, None
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


def enu_heading_rad(course_deg: float) -> float:
    """NMEA course or heading (from north, clockwise, degrees) -> ENU heading (from east, anticlockwise)."""
    return math.pi / 2.0 - math.radians(course_deg)
