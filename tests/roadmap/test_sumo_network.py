"""SUMO networks as road maps: networks built at test time by netgenerate, read through sumolib into a RoadMap, and
the lanes checked against what netgenerate was told and against sumolib's own latitude and longitude."""

import sys

import numpy as np
import pyproj
import pytest
import sumolib

from coopdrive.roadmap import RoadMap
from coopdrive.roadmap.sumo_lane import SumoLane
from coopdrive.roadmap.sumo_network import SumoNetworkError, check_sumo_network, map_parts_of, read_sumo_network
from tests.sumo_networks import (ASTAZERO_LAT_LON_DEG, GRID_LANE_WIDTH_M, GRID_NODES, GRID_SPEED_MPS,
                                 STRAIGHT_LANE_WIDTH_M, STRAIGHT_LANES, STRAIGHT_LENGTH_M, STRAIGHT_SPEED_MPS,
                                 footpaths_only, geo_referenced, grid_with_sidewalks, straight_road)

WGS84 = pyproj.Geod(ellps="WGS84")
# 1e-8 deg is about 1 mm: the unprojection and the ENU frame agree to well below it.
LAT_LON_TOLERANCE_DEG = 1e-8


def map_of(parts) -> RoadMap:
    origin, lanes, successors = parts
    return RoadMap(origin, lanes, successors=successors)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("sumo")


@pytest.fixture(scope="module")
def straight(folder):
    return straight_road(folder / "straight.net.xml")


@pytest.fixture(scope="module")
def geo_straight(folder):
    return geo_referenced(straight_road(folder / "geo_straight.net.xml"), *ASTAZERO_LAT_LON_DEG)


@pytest.fixture(scope="module")
def grid(folder):
    return grid_with_sidewalks(folder / "grid.net.xml")


def test_a_straight_road_from_netgenerate_has_two_lanes_each_way_of_the_width_speed_and_length_it_was_given(straight):
    road_map = RoadMap.load(straight)
    assert road_map.name == "straight"
    assert sorted({lane.road_id for lane in road_map.lanes}) == ["A0B0", "B0A0"]
    for road in ("A0B0", "B0A0"):
        lanes = road_map.lanes_of_road(road)
        assert [lane.lane_index for lane in lanes] == list(range(STRAIGHT_LANES))
        assert [lane.lane_id for lane in lanes] == [f"{road}_{index}" for index in range(STRAIGHT_LANES)]
        for lane in lanes:
            assert lane.width_m == pytest.approx(STRAIGHT_LANE_WIDTH_M)
            assert lane.speed_limit_mps == pytest.approx(STRAIGHT_SPEED_MPS)
            assert lane.length_m == pytest.approx(STRAIGHT_LENGTH_M, abs=0.01)


def test_lane_zero_is_the_rightmost_as_in_our_maps(straight):
    road_map = RoadMap.load(straight)
    right, left = road_map.lanes_of_road("A0B0")
    station_m = 1000.0
    x_m, y_m, _ = right.pose_at(station_m)
    assert left.project_full(x_m, y_m).lateral_offset_m == pytest.approx(-STRAIGHT_LANE_WIDTH_M)
    assert road_map.match(*right.pose_at(station_m)).lane is right


def test_a_network_without_projection_keeps_its_coordinates_as_metres_about_the_default_origin(straight):
    road_map = RoadMap.load(straight)
    net = sumolib.net.readNet(str(straight))
    for lane in road_map.lanes:
        assert lane.points_xy.tolist() == [list(point) for point in net.getLane(lane.lane_id).getShape()]
    assert road_map.origin == pytest.approx((51.4758, 5.6247, 20.0))


def test_a_geo_referenced_network_s_lanes_start_where_sumolib_puts_them_in_latitude_and_longitude(geo_straight):
    road_map = RoadMap.load(geo_straight)
    net = sumolib.net.readNet(str(geo_straight))
    for lane in road_map.lanes:
        lon_deg, lat_deg = net.convertXY2LonLat(*net.getLane(lane.lane_id).getShape()[0])
        lat, lon, _ = road_map.to_geodetic(*lane.points_xy[0])
        assert (lat, lon) == pytest.approx((lat_deg, lon_deg), abs=LAT_LON_TOLERANCE_DEG)
    assert road_map.origin[:2] == pytest.approx(net.convertXY2LonLat(1000.0, 0.0)[::-1], abs=LAT_LON_TOLERANCE_DEG)
    # The road's middle, 1 km east of its start where the network was laid.
    assert road_map.origin[:2] == pytest.approx(ASTAZERO_LAT_LON_DEG, abs=0.02)


def test_a_geo_referenced_lane_is_as_long_as_the_ground_between_its_ends_not_as_its_utm_length(geo_straight):
    road_map = RoadMap.load(geo_straight)
    net = sumolib.net.readNet(str(geo_straight))
    lane = road_map.lane("A0B0_0")
    (x0, y0), (x1, y1) = net.getLane("A0B0_0").getShape()
    (lon0, lat0), (lon1, lat1) = net.convertXY2LonLat(x0, y0), net.convertXY2LonLat(x1, y1)
    _, _, ground_m = WGS84.inv(lon0, lat0, lon1, lat1)
    assert lane.length_m == pytest.approx(ground_m, abs=0.01)
    # UTM's scale 2.2 deg west of zone 33's central meridian: the projected 2 km are 0.4 m short of the ground's.
    assert lane.length_m - STRAIGHT_LENGTH_M == pytest.approx(0.38, abs=0.05)


def test_a_grid_with_sidewalks_keeps_one_drivable_lane_per_edge_numbered_from_zero(grid):
    road_map = RoadMap.load(grid)
    net = sumolib.net.readNet(str(grid))
    edges = [edge for edge in net.getEdges(withInternal=False) if edge.getFunction() == ""]
    assert len(edges) == 4 * GRID_NODES * (GRID_NODES - 1)
    assert len(road_map.lanes) == len(edges)
    for lane in road_map.lanes:
        sumo_lane = net.getLane(lane.lane_id)
        assert (lane.lane_index, sumo_lane.getIndex()) == (0, 1)
        assert lane.width_m == pytest.approx(GRID_LANE_WIDTH_M)
        assert lane.speed_limit_mps == pytest.approx(GRID_SPEED_MPS)
        assert lane.length_m == pytest.approx(sumo_lane.getLength(), abs=0.01)


def test_a_grid_s_connections_through_its_junctions_are_the_map_s_successors(grid):
    road_map = RoadMap.load(grid)
    # From the south-west corner north to the middle of the west side: on north, right to the east, or back.
    assert set(road_map.successors["A0A1_1"]) == {"A1A2_1", "A1B1_1", "A1A0_1"}
    assert all(set(successors) <= {lane.lane_id for lane in road_map.lanes}
               for successors in road_map.successors.values())


def test_lanes_that_no_car_may_use_are_left_out_and_the_rest_numbered_from_the_right_without_a_network():
    lanes = [SumoLane("e_0", "e", 0, ((0.0, -4.0), (50.0, -4.0)), 2.0, 1.5, drivable=False),
             SumoLane("e_1", "e", 1, ((0.0, -1.5), (50.0, -1.5)), 3.0, 13.9, drivable=True, successor_ids=("f_1",)),
             SumoLane("f_0", "f", 0, ((50.0, 4.0), (0.0, 4.0)), 2.0, 1.5, drivable=False),
             SumoLane("f_1", "f", 1, ((50.0, 1.5), (0.0, 1.5)), 3.0, 13.9, drivable=True, successor_ids=("e_0",))]
    road_map = map_of(map_parts_of(lanes, None, (25.0, 0.0)))
    assert [(lane.lane_id, lane.road_id, lane.lane_index) for lane in road_map.lanes] == [("e_1", "e", 0),
                                                                                          ("f_1", "f", 0)]
    assert road_map.successors == {"e_1": ("f_1",), "f_1": ()}


def test_a_projection_puts_the_origin_at_the_network_s_centre_and_the_lanes_about_it_without_a_network():
    lat0_deg, lon0_deg = 45.0, 7.0
    # A transverse Mercator about the origin: true to scale there, as the ENU frame is.
    mercator = pyproj.Proj(f"+proj=tmerc +lat_0={lat0_deg} +lon_0={lon0_deg} +ellps=WGS84")

    def to_lon_lat(x_m: np.ndarray, y_m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return mercator(x_m, y_m, inverse=True)

    lane = SumoLane("e_0", "e", 0, ((-100.0, 0.0), (100.0, 0.0)), 3.5, 20.0, drivable=True)
    road_map = map_of(map_parts_of([lane], to_lon_lat, (0.0, 0.0)))
    assert road_map.origin == pytest.approx((lat0_deg, lon0_deg, 0.0))
    (start_x_m, start_y_m), (end_x_m, end_y_m) = road_map.lanes[0].points_xy
    assert (start_x_m, end_x_m) == pytest.approx((-100.0, 100.0), abs=0.001)
    # The ENU frame is a plane tangent at the origin: 100 m away the ground has dropped 0.8 mm below it.
    assert (start_y_m, end_y_m) == pytest.approx((0.0, 0.0), abs=0.001)


def test_a_missing_file_is_one_line_naming_it_and_an_os_error_as_a_missing_geojson_map_s_is(folder):
    with pytest.raises(SumoNetworkError, match=r"nowhere\.net\.xml: no such SUMO network file$") as error:
        RoadMap.load(folder / "nowhere.net.xml")
    assert isinstance(error.value, FileNotFoundError)


@pytest.mark.parametrize("text, problem", [
    ('<routes><vehicle id="a" depart="0"/></routes>\n', "not a SUMO network (its root element is <routes>, not <net>)"),
    ('{"type": "FeatureCollection"}\n',
     "not a SUMO network (not XML: not well-formed (invalid token): line 1, column 0)"),
    ("", "not a SUMO network (not XML: no element found: line 1, column 0)"),
], ids=["routes", "json", "empty"])
def test_a_file_that_is_not_a_sumo_network_is_one_line_saying_so(folder, text, problem):
    path = folder / "routes.net.xml"
    path.write_text(text)
    with pytest.raises(SumoNetworkError) as error:
        read_sumo_network(path)
    assert str(error.value) == f"{path}: {problem}"


def test_a_network_of_footpaths_only_is_one_line_saying_it_has_no_drivable_lane(folder):
    path = footpaths_only(folder / "footpaths.net.xml")
    with pytest.raises(SumoNetworkError) as error:
        read_sumo_network(path)
    assert str(error.value) == f"{path}: the SUMO network has no drivable lane (8 lanes, none that a passenger car " \
                               "may use)"


def test_without_sumolib_a_network_is_one_line_naming_the_package_to_install(straight, monkeypatch):
    # None in sys.modules makes `import sumolib` fail as it does where the package is not installed.
    monkeypatch.setitem(sys.modules, "sumolib", None)
    with pytest.raises(SumoNetworkError) as error:
        read_sumo_network(straight)
    assert str(error.value) == (f"{straight}: reading a SUMO network needs sumolib, which is not installed "
                                "(pip install 'sumolib>=1.28,<1.29')")


def test_a_network_checked_once_is_not_read_again_until_its_file_changes(folder, monkeypatch):
    path = straight_road(folder / "checked.net.xml")
    check_sumo_network(path)
    # Without sumolib a read would fail: the unchanged file is not read again, the rewritten one is.
    monkeypatch.setitem(sys.modules, "sumolib", None)
    check_sumo_network(path)
    path.write_text(path.read_text(encoding="utf-8") + "<!-- changed -->\n", encoding="utf-8")
    with pytest.raises(SumoNetworkError, match="needs sumolib"):
        check_sumo_network(path)
