"""Scene lane indices count only on the ego's own road (T-intersection map: main road east-west, side road
coming up from the south to the reference point at the origin)."""

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.scene.road_lanes import EgoRoadLanes
from coopdrive.v1 import ego_pb2


@pytest.fixture(scope="module")
def road_map():
    return RoadMap.load("intersection")


def lanes_for_ego_at(road_map, x_m, y_m, heading_rad):
    lanes = EgoRoadLanes(road_map)
    match = road_map.match(x_m, y_m, heading_rad)
    lanes.on_ego(ego_pb2.EgoState(lane=ego_pb2.LanePosition(matched=True, lane_index=match.lane_index,
                                                            road_id=match.lane.road_id)))
    return lanes, match


def test_a_car_ahead_on_the_ego_road_is_in_its_lane(road_map):
    lanes, match = lanes_for_ego_at(road_map, -80.0, -1.75, 0.0)
    assert lanes.lane_of(-40.0, -1.75) == match.lane_index


def test_a_car_waiting_on_the_side_road_has_no_lane_for_an_ego_on_the_main_road(road_map):
    lanes, _ = lanes_for_ego_at(road_map, -80.0, -1.75, 0.0)
    side = road_map.match(1.75, -20.0, 1.5708)
    assert side is not None and side.lane_index == 0
    assert lanes.lane_of(1.75, -20.0) is None


def test_before_the_ego_is_matched_any_road_counts(road_map):
    assert EgoRoadLanes(road_map).lane_of(1.75, -20.0) == 0
