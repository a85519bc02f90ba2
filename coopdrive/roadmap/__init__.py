"""Lane-level road maps (GeoJSON, WGS84) used in the local ENU frame."""

from coopdrive.roadmap.lane import Lane, wrap_angle_rad
from coopdrive.roadmap.road_map import LaneMatch, RoadMap, Zone

__all__ = ["Lane", "LaneMatch", "RoadMap", "Zone", "wrap_angle_rad"]
