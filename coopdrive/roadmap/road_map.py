"""A lane-level road map read from GeoJSON (WGS84), used in the local ENU frame around its origin.

GeoJSON layout (one FeatureCollection):
- top-level member "origin": {"lat_deg", "lon_deg", "alt_m"}, the ENU origin (else the first lane point);
- each lane a LineString in driving order with properties
  {road_id, lane_id, lane_index (0 = rightmost), width_m, speed_limit_mps};
- optional Point features {kind: "reference_point" | "zone", name, radius_m} and Polygon features
  {kind: "zone", name}: every feature with a name and a radius (or a polygon) is a zone.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

import numpy as np
import pymap3d

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap.lane import Lane, wrap_angle_rad
from coopdrive.roadmap.sumo_network import names_sumo_network, read_sumo_network, sumo_map_name

MAP_PACKAGE = "coopdrive.maps"
MAP_SUFFIX = ".geojson"
# A vehicle changing lanes is rarely more than 30 deg off the lane; the opposite lane is 180 deg off.
HEADING_GATE_RAD = math.radians(60.0)
# Lanes whose bounding box is further than this from the point are not projected at all.
BBOX_MARGIN_M = 10.0


@dataclass(frozen=True)
class LaneMatch:
    lane: Lane
    lane_index: int
    station_m: float
    lateral_offset_m: float
    heading_error_rad: float
    curvature_1pm: float


@dataclass(frozen=True)
class Zone:
    """A named area (competition zone, reference point) with a centre and a radius, ENU metres."""

    name: str
    x_m: float
    y_m: float
    radius_m: float
    polygon_xy: tuple[tuple[float, float], ...] = ()

    def contains(self, x_m: float, y_m: float) -> bool:
        if self.polygon_xy:
            return _inside_polygon(x_m, y_m, self.polygon_xy)
        return math.hypot(x_m - self.x_m, y_m - self.y_m) <= self.radius_m


def _inside_polygon(x_m: float, y_m: float, ring: tuple[tuple[float, float], ...]) -> bool:
    inside = False
    for (x1, y1), (x2, y2) in zip(ring, ring[1:] + ring[:1]):
        if (y1 > y_m) != (y2 > y_m) and x_m < x1 + (y_m - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


class RoadMap:
    def __init__(self, origin: tuple[float, float, float], lanes: list[Lane], zones: dict[str, Zone] | None = None,
                 name: str = "", successors: dict[str, tuple[str, ...]] | None = None) -> None:
        self.origin = origin
        self._plane = LocalTangentPlane(*origin)
        self.lanes = lanes
        self.zones = zones or {}
        self.name = name
        # lane_id -> the lanes a vehicle may go on to from its end (a SUMO network's connections; GeoJSON has none).
        self.successors = successors or {}
        ids = [lane.lane_id for lane in lanes]
        if len(set(ids)) != len(ids):
            raise ValueError(f"map {name!r} has duplicate lane_id values")
        self._by_id = {lane.lane_id: lane for lane in lanes}

    # --- loading -------------------------------------------------------------------------------
    @classmethod
    def load(cls, path_or_name: str | Path) -> RoadMap:
        """A file path (GeoJSON, or a SUMO network: sumo_network.py), or a bare name ("a270") of a map shipped in
        coopdrive.maps."""
        text_path = str(path_or_name)
        if names_sumo_network(text_path):
            origin, lanes, successors = read_sumo_network(text_path)
            return cls(origin, lanes, name=sumo_map_name(text_path), successors=successors)
        if isinstance(path_or_name, Path) or "/" in text_path or text_path.endswith(MAP_SUFFIX):
            data = json.loads(Path(text_path).read_text())
            name = Path(text_path).stem
        else:
            resource = files(MAP_PACKAGE) / f"{text_path}{MAP_SUFFIX}"
            if not resource.is_file():
                raise FileNotFoundError(f"no shipped map named {text_path!r} in {MAP_PACKAGE}")
            data = json.loads(resource.read_text())
            name = text_path
        return cls.from_geojson(data, name=name)

    @classmethod
    def from_geojson(cls, data: dict, name: str = "") -> RoadMap:
        if data.get("type") != "FeatureCollection":
            raise ValueError(f"map {name!r} is not a GeoJSON FeatureCollection")
        features = data.get("features", [])
        origin = _origin_of(data, features, name)
        lanes: list[Lane] = []
        zones: dict[str, Zone] = {}
        for feature in features:
            geometry = feature.get("geometry") or {}
            props = feature.get("properties") or {}
            kind = geometry.get("type")
            coords = np.asarray(geometry.get("coordinates", []), dtype=float)
            if kind == "LineString":
                lanes.append(_lane_from(coords, props, origin))
            elif kind == "Point" and "name" in props:
                x_m, y_m = _to_enu_xy(coords.reshape(1, -1), origin)[0]
                zones[props["name"]] = Zone(props["name"], float(x_m), float(y_m), float(props.get("radius_m", 0.0)))
            elif kind == "Polygon" and "name" in props:
                ring = _to_enu_xy(coords[0], origin)
                centre = ring.mean(axis=0)
                radius_m = float(np.max(np.linalg.norm(ring - centre, axis=1)))
                zones[props["name"]] = Zone(props["name"], float(centre[0]), float(centre[1]), radius_m,
                                            tuple((float(x), float(y)) for x, y in ring))
        return cls(origin, lanes, zones, name=name or data.get("name", ""))

    # --- frames --------------------------------------------------------------------------------
    def to_enu(self, lat_deg: float, lon_deg: float, alt_m: float = 0.0) -> tuple[float, float, float]:
        return self._plane.to_enu(lat_deg, lon_deg, alt_m)

    def to_geodetic(self, x_m: float, y_m: float, z_m: float = 0.0) -> tuple[float, float, float]:
        return self._plane.to_geodetic(x_m, y_m, z_m)

    # --- queries -------------------------------------------------------------------------------
    def lane(self, lane_id: str) -> Lane:
        return self._by_id[lane_id]

    def lanes_of_road(self, road_id: str) -> list[Lane]:
        """Lanes of one road ordered by lane_index (rightmost first)."""
        return sorted((lane for lane in self.lanes if lane.road_id == road_id), key=lambda lane: lane.lane_index)

    def match(self, x_m: float, y_m: float, heading_rad: float | None = None) -> LaneMatch | None:
        """The lane whose half width holds the point (and whose direction agrees with heading_rad)."""
        best: LaneMatch | None = None
        for lane in self.lanes:
            if not lane.near_bbox(x_m, y_m, BBOX_MARGIN_M + lane.width_m):
                continue
            p = lane.project_full(x_m, y_m)
            if abs(p.lateral_offset_m) > 0.5 * lane.width_m or not 0.0 <= p.station_m <= lane.length_m:
                continue
            heading_error = 0.0 if heading_rad is None else wrap_angle_rad(heading_rad - p.heading_rad)
            if abs(heading_error) > HEADING_GATE_RAD:
                continue
            if best is None or abs(p.lateral_offset_m) < abs(best.lateral_offset_m):
                best = LaneMatch(lane, lane.lane_index, p.station_m, p.lateral_offset_m, heading_error,
                                 p.curvature_1pm)
        return best


def _origin_of(data: dict, features: list, name: str) -> tuple[float, float, float]:
    origin = data.get("origin")
    if origin is not None:
        return float(origin["lat_deg"]), float(origin["lon_deg"]), float(origin.get("alt_m", 0.0))
    for feature in features:
        geometry = feature.get("geometry") or {}
        if geometry.get("type") == "LineString":
            lon, lat, *alt = geometry["coordinates"][0]
            return float(lat), float(lon), float(alt[0]) if alt else 0.0
    raise ValueError(f"map {name!r} has neither an origin nor a lane")


def _to_enu_xy(coords_lon_lat: np.ndarray, origin: tuple[float, float, float]) -> np.ndarray:
    lon = coords_lon_lat[:, 0]
    lat = coords_lon_lat[:, 1]
    alt = coords_lon_lat[:, 2] if coords_lon_lat.shape[1] > 2 else np.full(len(lon), origin[2])
    e, n, _ = pymap3d.geodetic2enu(lat, lon, alt, *origin)
    return np.column_stack((np.atleast_1d(e), np.atleast_1d(n)))


_LANE_KEYS = ("road_id", "lane_id", "lane_index", "width_m")


def _lane_from(coords: np.ndarray, props: dict, origin: tuple[float, float, float]) -> Lane:
    missing = [key for key in _LANE_KEYS if key not in props]
    if missing:
        raise ValueError(f"lane feature {props.get('lane_id', '?')!r} lacks properties {missing}")
    return Lane(
        lane_id=str(props["lane_id"]),
        road_id=str(props["road_id"]),
        lane_index=int(props["lane_index"]),
        width_m=float(props["width_m"]),
        points_xy=_to_enu_xy(coords, origin),
        speed_limit_mps=float(props.get("speed_limit_mps", 0.0)),
    )
