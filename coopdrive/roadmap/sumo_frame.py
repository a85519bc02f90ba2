"""Between a SUMO network's own coordinates and the local frame its road map is laid in, both ways.

The network loader (sumo_network.py) lays a network in the local frame so: a network without a projection keeps its
coordinates as local metres; a geo-referenced one is unprojected by sumolib (net.convertXY2LonLat) and put in the
road map's tangent plane. SumoFrame is that transformation and its inverse (the road map's plane back to latitude and
longitude, projected by sumolib's net.convertLonLat2XY), for what talks to SUMO in its coordinates (libsumo).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Protocol


class GeodeticPlane(Protocol):
    """What SumoFrame needs of the road map laid from the network (coopdrive.roadmap.RoadMap)."""

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
        if self._net is None:
            return x_m, y_m
        lon_deg, lat_deg = self._net.convertXY2LonLat(x_m, y_m)
        east_m, north_m, _ = self._plane.to_enu(float(lat_deg), float(lon_deg))
        return float(east_m), float(north_m)

    def to_network(self, x_m: float, y_m: float) -> tuple[float, float]:
        if self._net is None:
            return x_m, y_m
        lat_deg, lon_deg, _ = self._plane.to_geodetic(x_m, y_m)
        network_x_m, network_y_m = self._net.convertLonLat2XY(lon_deg, lat_deg)
        return float(network_x_m), float(network_y_m)
