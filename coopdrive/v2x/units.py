"""Every conversion between wire units and SI, in one place.

A wire INTEGER field is described once (scale, valid range, special codes); `to_wire` clamps to the
valid range and maps None (or NaN) to the field's "unavailable" code, `to_si` maps that code back to None
and an "outOfRange" code to +inf. Headings: ETSI counts 0.1 deg from north, clockwise; inside the stack
heading is the ENU yaw in rad (0 = east, counter-clockwise positive).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from coopdrive.v2x.reasons import V2xEncodeError

KPH_PER_MPS = 3.6
# Latitudes and longitudes on the wire (ETSI, IEEE 1609.2) count tenths of a microdegree.
TENTH_MICRODEG_PER_DEG = 10_000_000
# The mean Earth radius (IUGG), for distances between nearby positions on a sphere.
EARTH_RADIUS_M = 6_371_008.8
_LARGEST_COUNT = 2.0**53


@dataclass(frozen=True)
class LinearField:
    """si = count * si_per_count for min_count <= count <= max_count."""

    si_per_count: float
    min_count: int
    max_count: int
    unavailable: int | None = None
    out_of_range: int | None = None

    def to_wire(self, si: float | None) -> int:
        if si is None or si != si:  # si != si: NaN
            if self.unavailable is None:
                raise V2xEncodeError(f"{si} for a field with no 'unavailable' value ({self})")
            return self.unavailable
        scaled = si / self.si_per_count
        if not -_LARGEST_COUNT < scaled < _LARGEST_COUNT:  # infinities, and magnitudes no field could hold
            scaled = math.copysign(_LARGEST_COUNT, scaled)
        count = round(scaled)
        # Comparisons rather than min(max()): this runs for every field of every 25 Hz message.
        if count > self.max_count:
            return self.max_count if self.out_of_range is None else self.out_of_range
        if count < self.min_count:
            return self.min_count
        return count

    def to_si(self, count: int) -> float | None:
        if count == self.unavailable:
            return None
        if count == self.out_of_range:
            return math.inf
        return count * self.si_per_count


@dataclass(frozen=True)
class ConfidenceClasses:
    """An ENUMERATED confidence: each class name stands for 'within this bound' (SI)."""

    classes: tuple[tuple[str, float], ...]
    out_of_range: str = "outOfRange"
    unavailable: str = "unavailable"

    def to_wire(self, bound_si: float | None) -> str:
        if bound_si is None or math.isnan(bound_si):
            return self.unavailable
        for name, bound in self.classes:
            if bound_si <= bound * (1 + 1e-9):
                return name
        return self.out_of_range

    def to_si(self, name: str) -> float | None:
        return self._bound_of_name[name]

    @functools.cached_property
    def _bound_of_name(self) -> dict[str, float | None]:
        return {**dict(self.classes), self.out_of_range: math.inf, self.unavailable: None}


# Positions: 0.1 microdegree.
LATITUDE_TENTH_MICRODEG = LinearField(1e-7, -900_000_000, 900_000_000, unavailable=900_000_001)
LONGITUDE_TENTH_MICRODEG = LinearField(1e-7, -1_800_000_000, 1_800_000_000, unavailable=1_800_000_001)
DELTA_LATITUDE_TENTH_MICRODEG = LinearField(1e-7, -131_071, 131_071, unavailable=131_072)
DELTA_LONGITUDE_TENTH_MICRODEG = LinearField(1e-7, -131_071, 131_071, unavailable=131_072)
ALTITUDE_CM = LinearField(0.01, -100_000, 800_000, unavailable=800_001)
DELTA_ALTITUDE_CM = LinearField(0.01, -12_700, 12_799, unavailable=12_800)
SEMI_AXIS_LENGTH_CM = LinearField(0.01, 0, 4093, unavailable=4095, out_of_range=4094)
ALTITUDE_CONFIDENCE = ConfidenceClasses(tuple(
    (name, bound) for name, bound in [
        ("alt-000-01", 0.01), ("alt-000-02", 0.02), ("alt-000-05", 0.05), ("alt-000-10", 0.1),
        ("alt-000-20", 0.2), ("alt-000-50", 0.5), ("alt-001-00", 1.0), ("alt-002-00", 2.0),
        ("alt-005-00", 5.0), ("alt-010-00", 10.0), ("alt-020-00", 20.0), ("alt-050-00", 50.0),
        ("alt-100-00", 100.0), ("alt-200-00", 200.0)]))
PATH_DELTA_TIME_10MS = LinearField(0.01, 1, 65_535)

# Kinematics.
SPEED_CMPS = LinearField(0.01, 0, 16_382, unavailable=16_383)
SPEED_CONFIDENCE_CMPS = LinearField(0.01, 1, 125, unavailable=127, out_of_range=126)
HEADING_CONFIDENCE_TENTH_DEG = LinearField(math.radians(0.1), 1, 125, unavailable=127, out_of_range=126)
ACCELERATION_DECIMPS2 = LinearField(0.1, -160, 160, unavailable=161)
ACCELERATION_CONFIDENCE_DECIMPS2 = LinearField(0.1, 0, 100, unavailable=102, out_of_range=101)
# ETSI yaw rate and steering angle count left (counter-clockwise) positive, like ENU.
YAW_RATE_CENTIDEGPS = LinearField(math.radians(0.01), -32_766, 32_766, unavailable=32_767)
YAW_RATE_CONFIDENCE = ConfidenceClasses(tuple(
    (name, math.radians(bound_degps)) for name, bound_degps in [
        ("degSec-000-01", 0.01), ("degSec-000-05", 0.05), ("degSec-000-10", 0.1), ("degSec-001-00", 1.0),
        ("degSec-005-00", 5.0), ("degSec-010-00", 10.0), ("degSec-100-00", 100.0)]))
STEERING_WHEEL_ANGLE_1_5DEG = LinearField(math.radians(1.5), -511, 511, unavailable=512)
STEERING_WHEEL_ANGLE_CONFIDENCE_1_5DEG = LinearField(math.radians(1.5), 1, 125, unavailable=127, out_of_range=126)
# Curvature changed unit between the CDD versions: v1 counts 1/30000 per m, v2 1/10000 per m.
CURVATURE_V1_PER_30000M = LinearField(1 / 30_000, -30_000, 30_000, unavailable=30_001)
CURVATURE_V2_PER_10000M = LinearField(1e-4, -1023, 1022, unavailable=1023)
CURVATURE_CONFIDENCE = ConfidenceClasses((
    ("onePerMeter-0-00002", 0.00002), ("onePerMeter-0-0001", 0.0001), ("onePerMeter-0-0005", 0.0005),
    ("onePerMeter-0-002", 0.002), ("onePerMeter-0-01", 0.01), ("onePerMeter-0-1", 0.1)))

# Vehicle and event.
VEHICLE_LENGTH_DM = LinearField(0.1, 1, 1021, unavailable=1023, out_of_range=1022)
VEHICLE_WIDTH_DM = LinearField(0.1, 1, 60, unavailable=62, out_of_range=61)
VALIDITY_DURATION_S = LinearField(1.0, 0, 86_400)
TRANSMISSION_INTERVAL_MS = LinearField(0.001, 1, 10_000)
TEMPERATURE_DEGC = LinearField(1.0, -60, 67)
SPEED_LIMIT_KPH = LinearField(1 / KPH_PER_MPS, 1, 255)

# iCLCM (GCDC 2016).
ICLCM_REAR_AXLE_LOCATION_CM = LinearField(0.01, 0, 4095)
ICLCM_RESPONSE_TIME_10MS = LinearField(0.01, 0, 1000, unavailable=1001)
ICLCM_TARGET_ACCELERATION_CMPS2 = LinearField(0.01, -1000, 1000, unavailable=1001)
ICLCM_TIME_HEADWAY_100MS = LinearField(0.1, 0, 360, unavailable=361)
ICLCM_CRUISE_SPEED_CMPS = LinearField(0.01, 0, 5000, unavailable=5001)
ICLCM_MIO_RANGE_CM = LinearField(0.01, 0, 65_534, unavailable=65_535)
# The wire counts 2 mrad to the right; inside the stack left is positive, hence the negative scale.
ICLCM_MIO_BEARING_2MRAD_RIGHT = LinearField(-0.002, -1571, 1571, unavailable=1572)
ICLCM_MIO_RANGE_RATE_CMPS = LinearField(0.01, -32_767, 32_766, unavailable=32_767)
ICLCM_DISTANCE_TRAVELLED_CZ_DM = LinearField(0.1, 0, 10_000)
ICLCM_LANE = LinearField(1.0, 1, 3, unavailable=4)

# GeoNetworking long position vector: 15-bit signed speed, 16-bit heading without 'unavailable'.
GN_SPEED_CMPS = LinearField(0.01, -16_384, 16_383)

# DSRC types of TS 103 301 (MAPEM, SPATEM, SREM, SSEM). Node offsets (Offset-B10 to Offset-B16, DrivenLineOffset)
# and lane widths count centimetres; the CHOICE of the node says the width, the scale is the same.
DSRC_OFFSET_CM = LinearField(0.01, -32_768, 32_767)
DSRC_LANE_WIDTH_CM = LinearField(0.01, 0, 32_767)
DSRC_ELEVATION_DM = LinearField(0.1, -4095, 61_439, unavailable=-4096)
# TimeMark: tenths of a second after the start of the UTC hour; 35991..36000 during a leap second, 36001 unknown.
TIME_MARK_DS = LinearField(0.1, 0, 36_000, unavailable=36_001)
# DSecond: milliseconds within the minute (60000..60999 during a leap second), 65535 unavailable.
DSECOND_MS = LinearField(0.001, 0, 65_534, unavailable=65_535)

HEADING_UNAVAILABLE_TENTH_DEG = 3601
_TENTH_DEG_PER_TURN = 3600


def heading_enu_rad_to_etsi_tenth_deg(heading_rad: float | None) -> int:
    """ENU yaw (east, counter-clockwise) -> ETSI HeadingValue (north, clockwise, 0.1 deg, 0..3599)."""
    if heading_rad is None or not math.isfinite(heading_rad):
        return HEADING_UNAVAILABLE_TENTH_DEG
    # Wrapped in radians first: degrees() of a huge angle overflows to infinity.
    north_clockwise_deg = (90.0 - math.degrees(math.remainder(heading_rad, math.tau))) % 360.0
    return round(north_clockwise_deg * 10) % _TENTH_DEG_PER_TURN


def etsi_tenth_deg_to_heading_enu_rad(count: int) -> float | None:
    """ETSI HeadingValue -> ENU yaw in (-pi, pi]; None for 'unavailable'."""
    if count == HEADING_UNAVAILABLE_TENTH_DEG:
        return None
    heading_rad = math.radians(90.0 - count / 10.0)
    wrapped = math.remainder(heading_rad, math.tau)
    return math.pi if wrapped == -math.pi else wrapped
