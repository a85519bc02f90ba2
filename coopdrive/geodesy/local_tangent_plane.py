"""LocalTangentPlane: WGS84 geodetic <-> local ENU about a fixed origin, in plain float math.

pymap3d computes the same transforms for arrays; per scalar call its ecef2geodetic costs ~0.2 ms, which
the 50 Hz ego-state output cannot afford. Here the origin's ECEF position and rotation are computed once,
and ECEF -> geodetic uses Bowring's closed form (one iteration is sub-millimetre near the Earth's surface).
Tests check both directions against pymap3d.
"""

from __future__ import annotations

import math

import pymap3d

_ELLIPSOID = pymap3d.Ellipsoid.from_name("wgs84")
SEMI_MAJOR_M = _ELLIPSOID.semimajor_axis
SEMI_MINOR_M = _ELLIPSOID.semiminor_axis
E2 = 1.0 - (SEMI_MINOR_M / SEMI_MAJOR_M) ** 2  # first eccentricity squared
EP2 = (SEMI_MAJOR_M / SEMI_MINOR_M) ** 2 - 1.0  # second eccentricity squared


class LocalTangentPlane:
    def __init__(self, lat_deg: float, lon_deg: float, alt_m: float = 0.0):
        self.origin = (lat_deg, lon_deg, alt_m)
        self._x0, self._y0, self._z0 = (float(v) for v in pymap3d.geodetic2ecef(lat_deg, lon_deg, alt_m))
        lat, lon = math.radians(lat_deg), math.radians(lon_deg)
        self._sin_lat, self._cos_lat = math.sin(lat), math.cos(lat)
        self._sin_lon, self._cos_lon = math.sin(lon), math.cos(lon)

    def to_enu(self, lat_deg: float, lon_deg: float, alt_m: float = 0.0) -> tuple[float, float, float]:
        dx, dy, dz = (a - b for a, b in zip(_geodetic_to_ecef(lat_deg, lon_deg, alt_m),
                                             (self._x0, self._y0, self._z0)))
        sl, cl, so, co = self._sin_lat, self._cos_lat, self._sin_lon, self._cos_lon
        east = -so * dx + co * dy
        t = co * dx + so * dy
        north = -sl * t + cl * dz
        up = cl * t + sl * dz
        return east, north, up

    def to_geodetic(self, east_m: float, north_m: float, up_m: float = 0.0) -> tuple[float, float, float]:
        sl, cl, so, co = self._sin_lat, self._cos_lat, self._sin_lon, self._cos_lon
        t = -sl * north_m + cl * up_m
        x = self._x0 + co * t - so * east_m
        y = self._y0 + so * t + co * east_m
        z = self._z0 + cl * north_m + sl * up_m
        return _ecef_to_geodetic(x, y, z)


def _geodetic_to_ecef(lat_deg: float, lon_deg: float, alt_m: float) -> tuple[float, float, float]:
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    sin_lat, cos_lat = math.sin(lat), math.cos(lat)
    prime_vertical_m = SEMI_MAJOR_M / math.sqrt(1.0 - E2 * sin_lat * sin_lat)
    return ((prime_vertical_m + alt_m) * cos_lat * math.cos(lon),
            (prime_vertical_m + alt_m) * cos_lat * math.sin(lon),
            (prime_vertical_m * (1.0 - E2) + alt_m) * sin_lat)


def _ecef_to_geodetic(x: float, y: float, z: float) -> tuple[float, float, float]:
    """Bowring (1976): latitude from the parametric latitude in one step."""
    p = math.hypot(x, y)
    theta = math.atan2(z * SEMI_MAJOR_M, p * SEMI_MINOR_M)
    sin_t, cos_t = math.sin(theta), math.cos(theta)
    lat = math.atan2(z + EP2 * SEMI_MINOR_M * sin_t ** 3, p - E2 * SEMI_MAJOR_M * cos_t ** 3)
    sin_lat = math.sin(lat)
    prime_vertical_m = SEMI_MAJOR_M / math.sqrt(1.0 - E2 * sin_lat * sin_lat)
    cos_lat = math.cos(lat)
    if abs(cos_lat) > 1e-9:
        alt = p / cos_lat - prime_vertical_m
    else:
        alt = abs(z) - SEMI_MINOR_M
    return math.degrees(lat), math.degrees(math.atan2(y, x)), alt
