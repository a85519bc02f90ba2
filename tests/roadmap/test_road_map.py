import json
import math
from importlib.resources import files

import numpy as np
import pymap3d
import pytest

from coopdrive.roadmap import Lane, RoadMap
from coopdrive.roadmap import build_maps

ORIGIN = (51.47, 5.60, 20.0)


def two_lane_map() -> RoadMap:
    lanes = [Lane("r/0", "r", 0, 3.5, [[0.0, 0.0], [100.0, 0.0]]),
             Lane("r/1", "r", 1, 3.5, [[0.0, 3.5], [100.0, 3.5]])]
    return RoadMap(ORIGIN, lanes)


def test_a_point_is_matched_to_the_lane_whose_half_width_holds_it():
    match = two_lane_map().match(50.0, 2.0)
    assert match.lane.lane_id == "r/1"
    assert (match.lane_index, match.station_m, match.lateral_offset_m) == pytest.approx((1, 50.0, -1.5))
    assert two_lane_map().match(50.0, 1.0).lane_index == 0


def test_a_point_beside_the_road_or_past_its_end_is_not_matched():
    assert two_lane_map().match(50.0, 5.3) is None
    assert two_lane_map().match(101.0, 0.0) is None


def test_a_vehicle_driving_against_the_lane_direction_is_not_matched():
    assert two_lane_map().match(50.0, 0.0, heading_rad=math.pi) is None
    assert two_lane_map().match(50.0, 0.0, heading_rad=0.1).heading_error_rad == pytest.approx(0.1)


def test_lanes_of_a_road_come_rightmost_first():
    assert [lane.lane_id for lane in two_lane_map().lanes_of_road("r")] == ["r/0", "r/1"]


def test_a_geojson_lane_is_read_in_enu_around_the_declared_origin(tmp_path):
    lat, lon, _ = pymap3d.enu2geodetic(np.array([0.0, 100.0]), np.array([10.0, 10.0]), np.zeros(2), *ORIGIN)
    data = build_maps.collection("t", ORIGIN, [{
        "type": "Feature",
        "geometry": {"type": "LineString", "coordinates": [[lon[0], lat[0]], [lon[1], lat[1]]]},
        "properties": {"road_id": "t", "lane_id": "t/0", "lane_index": 0, "width_m": 3.0, "speed_limit_mps": 10.0},
    }])
    path = tmp_path / "t.geojson"
    path.write_text(json.dumps(data))
    road_map = RoadMap.load(path)
    lane = road_map.lanes[0]
    assert road_map.origin == ORIGIN
    assert lane.length_m == pytest.approx(100.0, abs=1e-3)
    assert lane.project(50.0, 12.0)[:2] == pytest.approx((50.0, 2.0), abs=1e-3)
    assert road_map.to_enu(*ORIGIN) == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert road_map.to_geodetic(*road_map.to_enu(51.471, 5.601, 22.0)) == pytest.approx((51.471, 5.601, 22.0))


def test_a_lane_feature_without_a_width_is_rejected():
    data = build_maps.collection("t", ORIGIN, [{
        "type": "Feature", "geometry": {"type": "LineString", "coordinates": [[5.6, 51.47], [5.601, 51.47]]},
        "properties": {"road_id": "t", "lane_id": "t/0", "lane_index": 0}}])
    with pytest.raises(ValueError, match="width_m"):
        RoadMap.from_geojson(data)


def test_an_unknown_shipped_map_name_is_a_clear_error():
    with pytest.raises(FileNotFoundError, match="nowhere"):
        RoadMap.load("nowhere")


def test_the_shipped_a270_has_two_parallel_lanes_of_about_four_kilometres():
    a270 = RoadMap.load("a270")
    right, left = a270.lanes_of_road("a270")
    assert (right.lane_index, left.lane_index) == (0, 1)
    assert right.width_m == left.width_m == 3.5
    assert right.length_m == pytest.approx(4000.0, abs=5.0)
    # The left lane lies one lane width left of the right lane, on the straight and on the curve.
    for station_m in (1000.0, 3500.0):
        x, y, _ = right.pose_at(station_m, 3.5)
        assert left.project(x, y)[1] == pytest.approx(0.0, abs=0.01)


def test_the_a270_is_straight_then_curves_gently_to_the_right():
    lane = RoadMap.load("a270").lanes[0]
    # Straight within the curvature of a 1000 km radius (the junction vertex spreads over the long segment).
    assert lane.project(*lane.pose_at(1000.0)[:2])[3] == pytest.approx(0.0, abs=1e-6)
    inner_radius_m = build_maps.A270_CURVE_RADIUS_M - 0.5 * build_maps.LANE_WIDTH_M
    assert lane.project(*lane.pose_at(3500.0)[:2])[3] == pytest.approx(-1.0 / inner_radius_m, rel=0.01)


@pytest.mark.parametrize("name", sorted(build_maps.BUILDERS))
def test_each_shipped_map_is_what_the_build_script_generates(name):
    shipped = json.loads(files("coopdrive.maps").joinpath(f"{name}.geojson").read_text())
    assert shipped == json.loads(json.dumps(build_maps.BUILDERS[name]()))


def test_the_intersection_map_has_a_competition_zone_around_its_reference_point():
    road_map = RoadMap.load("intersection")
    zone = road_map.zones["competition_zone"]
    reference = road_map.zones["intersection_reference_point"]
    assert (zone.x_m, zone.y_m) == pytest.approx((reference.x_m, reference.y_m), abs=1e-3)
    assert zone.contains(0.0, -50.0)
    assert not zone.contains(0.0, -150.0)


def test_the_intersection_map_matches_each_direction_to_its_own_lane():
    road_map = RoadMap.load("intersection")
    assert road_map.match(100.0, 1.75, heading_rad=math.pi).lane.road_id == "main_westbound"
    assert road_map.match(100.0, -1.75, heading_rad=0.0).lane.road_id == "main_eastbound"
    assert road_map.match(1.75, -50.0, heading_rad=math.pi / 2).lane.road_id == "side_northbound"
    assert road_map.match(1.75, -50.0, heading_rad=-math.pi / 2) is None
