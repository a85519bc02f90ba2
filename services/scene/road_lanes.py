"""Lane indices of scene objects, counted on the ego's own road.

Every road of a map numbers its lanes from 0, so "lane 0" alone would put a car waiting on a side road, or
one coming the other way, in the ego lane. A position matched to another road has no lane for the scene.
"""

from __future__ import annotations

from coopdrive.roadmap import RoadMap
from coopdrive.v1 import ego_pb2


class EgoRoadLanes:
    def __init__(self, road_map: RoadMap) -> None:
        self.road_map = road_map
        self.ego_road_id = ""

    def on_ego(self, ego: ego_pb2.EgoState) -> None:
        if ego.lane.matched and ego.lane.road_id:
            self.ego_road_id = ego.lane.road_id

    def lane_of(self, x_m: float, y_m: float) -> int | None:
        match = self.road_map.match(x_m, y_m)
        if match is None:
            return None
        if self.ego_road_id and match.lane.road_id != self.ego_road_id:
            return None
        return match.lane_index
