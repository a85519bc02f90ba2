import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.roadmap import Lane, RoadMap

L_SHAPE = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]])


def l_lane() -> Lane:
    return Lane("l/0", "l", 0, 3.5, L_SHAPE)


def arc_lane(radius_m: float, step_m: float, length_m: float) -> Lane:
    """Left-turning arc centred on (0, radius), starting at the origin heading east."""
    angles = np.arange(0.0, length_m / radius_m + 1e-12, step_m / radius_m)
    return Lane("arc/0", "arc", 0, 3.5, np.column_stack((radius_m * np.sin(angles), radius_m * (1 - np.cos(angles)))))


def test_a_lane_length_is_the_sum_of_its_segments():
    assert l_lane().length_m == pytest.approx(20.0)


def test_a_point_left_of_the_first_segment_projects_to_its_station_with_positive_offset():
    station, lateral, heading, _ = l_lane().project(5.0, 1.0)
    assert (station, lateral, heading) == pytest.approx((5.0, 1.0, 0.0))


def test_a_point_right_of_the_second_segment_has_a_negative_offset_and_its_heading():
    station, lateral, heading, _ = l_lane().project(12.0, 5.0)
    assert (station, lateral, heading) == pytest.approx((15.0, -2.0, math.pi / 2))


def test_a_point_outside_a_corner_projects_to_the_vertex_at_its_distance():
    station, lateral, _, _ = l_lane().project(11.0, -1.0)
    assert station == pytest.approx(10.0)
    assert lateral == pytest.approx(-math.sqrt(2.0))


def test_stations_extend_before_the_start_and_after_the_end():
    assert l_lane().project(-3.0, 2.0)[:2] == pytest.approx((-3.0, 2.0))
    assert l_lane().project(10.0, 14.0)[:2] == pytest.approx((24.0, 0.0))


def test_pose_at_a_station_and_offset_inverts_the_projection():
    assert l_lane().pose_at(15.0, 1.0) == pytest.approx((9.0, 5.0, math.pi / 2))
    assert l_lane().pose_at(5.0, -1.0) == pytest.approx((5.0, -1.0, 0.0))


def test_an_arc_reports_its_curvature_and_arc_length_station():
    lane = arc_lane(radius_m=100.0, step_m=1.0, length_m=60.0)
    # A point 2 m inside the arc at 0.3 rad: station 30 m, offset +2 m (left, toward the centre).
    x, y = 98.0 * math.sin(0.3), 100.0 - 98.0 * math.cos(0.3)
    station, lateral, heading, curvature = lane.project(x, y)
    assert station == pytest.approx(30.0, abs=0.01)
    assert lateral == pytest.approx(2.0, abs=0.01)
    assert heading == pytest.approx(0.3, abs=0.01)
    assert curvature == pytest.approx(0.01, rel=1e-3)


def test_a_straight_lane_has_zero_curvature():
    assert Lane("s", "s", 0, 3.5, [[0, 0], [5, 0], [10, 0]]).project(3.0, 1.0)[3] == 0.0


def test_a_lane_with_a_single_distinct_point_is_rejected_with_its_id():
    with pytest.raises(ValueError, match="bad"):
        Lane("bad", "r", 0, 3.5, [[1.0, 1.0], [1.0, 1.0]])


@functools.cache
def a270_right_lane() -> Lane:
    return RoadMap.load("a270").lanes_of_road("a270")[0]


@settings(max_examples=200, deadline=None)
@given(station_m=st.floats(0.0, 3990.0), lateral_m=st.floats(-1.75, 1.75))
def test_projecting_a_pose_on_the_a270_gives_back_its_station_and_offset(station_m, lateral_m):
    lane = a270_right_lane()
    x, y, heading = lane.pose_at(station_m, lateral_m)
    # Off the centre line, the inside of a polyline corner is a few millimetres off the true arc.
    assert lane.project(x, y)[:3] == pytest.approx((station_m, lateral_m, heading), abs=0.01)


def test_points_at_many_stations_are_pose_at_each_and_both_edges_at_one_lookup_are_each_edge_alone():
    import numpy as np

    from coopdrive.roadmap import RoadMap

    lane = RoadMap.load("a270").lanes[0]
    stations_m = np.array([-5.0, 0.0, 10.0, 123.4, lane.length_m, lane.length_m + 7.0])
    expected = [lane.pose_at(station_m, 1.5)[:2] for station_m in stations_m]
    assert np.allclose(lane.points_at(stations_m, 1.5), expected)
    both_edges = lane.points_at_offsets(stations_m, (1.75, -1.75))
    assert np.array_equal(both_edges, [lane.points_at(stations_m, 1.75), lane.points_at(stations_m, -1.75)])


def test_a_point_projected_again_gets_the_projection_remembered_and_a_fresh_lane_gives_the_same():
    lane = l_lane()
    rng = np.random.default_rng(3)
    points = [tuple(p) for p in rng.uniform(-2.0, 12.0, (600, 2))]  # more than a lane remembers
    first = [lane.project_full(x, y) for x, y in points]
    again = [lane.project_full(x, y) for x, y in points[-10:]]
    assert all(a is b for a, b in zip(again, first[-10:]))
    assert [l_lane().project_full(x, y) for x, y in points] == first
