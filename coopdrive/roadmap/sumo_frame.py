"""Between a SUMO network's own coordinates and the local frame its road map is laid in, both ways.

The network loader (sumo_network.py) lays a network in the local frame so: a network without a projection keeps its
coordinates as local metres; a geo-referenced one is unprojected by sumolib (net.convertXY2LonLat) and put in the
road map's tangent plane. SumoFrame is that transformation and its inverse (the road map's plane back to latitude and
longitude, projected by sumolib's net.convertLonLat2XY), for what talks to SUMO in its coordinates (libsumo).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Protocol

import numpy as np
import pymap3d


class GeodeticPlane(Protocol):
    """What SumoFrame needs of the road map laid from the network (coopdrive.roadmap.RoadMap)."""

    # The plane's geodetic origin (lat_deg, lon_deg, alt_m).
    origin: tuple[float, float, float]

    def to_enu(self, lat_deg: float, lon_deg: float, alt_m: float = 0.0) -> tuple[float, float, float]:
        ...

    def to_geodetic(self, x_m: float, y_m: float, z_m: float = 0.0) -> tuple[float, float, float]:
        ...


class SumoFrame:
    """network_xy (SUMO's x, y metres) <-> local_xy (the road map's ENU metres)."""

    def __init__(self, plane: GeodeticPlane, projected_net: Any | None = None) -> None:
        """projected_net: the sumolib network whose projection lays it (None: a network without a projection)."""
        self._plane = plane
        self._net = projected_net

    @classmethod
    def of_network(cls, path: str | Path, plane: GeodeticPlane) -> SumoFrame:
        """The frame of the network file that `plane` (its road map) was read from."""
        import sumolib

        net = sumolib.net.readNet(str(path), withInternal=False, withPrograms=False, withFoes=False,
                                  withConnections=False)
        return cls(plane, net if net.hasGeoProj() else None)

    def to_local(self, x_m: float, y_m: float) -> tuple[float, float]:
        east_m, north_m = self.to_local_many(np.array([[x_m, y_m]], dtype=float))[0]
        return float(east_m), float(north_m)

    def to_local_many(self, points_xy: np.ndarray) -> np.ndarray:
        """to_local of N points (N x 2) at once: a hundred SUMO vehicles a step cost one projection call, not a
        hundred."""
        if self._net is None or len(points_xy) == 0:
            return np.asarray(points_xy, dtype=float).reshape(-1, 2)
        lon_deg, lat_deg = self._net.convertXY2LonLat(points_xy[:, 0].copy(), points_xy[:, 1].copy())
        east_m, north_m, _ = pymap3d.geodetic2enu(np.asarray(lat_deg), np.asarray(lon_deg), np.zeros(len(points_xy)),
                                                  *self._plane.origin)
        return np.column_stack((np.atleast_1d(east_m), np.atleast_1d(north_m)))

    def to_network(self, x_m: float, y_m: float) -> tuple[float, float]:
        if self._net is None:
            return x_m, y_m
        lat_deg, lon_deg, _ = self._plane.to_geodetic(x_m, y_m)
        network_x_m, network_y_m = self._net.convertLonLat2XY(lon_deg, lat_deg)
        return float(network_x_m), float(network_y_m)
