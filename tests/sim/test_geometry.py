"""Ray casting of the simulated LiDAR, camera and sonars against vehicle footprints, checked by hand."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import array_shapes, arrays

from coopdrive.services.sim import geometry
from coopdrive.services.sim.geometry import cast_rays, ray_polygon_ranges


def square(centre_x_m: float, centre_y_m: float, half_side_m: float = 0.5) -> np.ndarray:
    x, y, h = centre_x_m, centre_y_m, half_side_m
    return np.array([[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]])


def test_a_ray_meets_the_near_face_of_a_square_and_misses_behind_it():
    ranges = ray_polygon_ranges((0.0, 0.0), np.array([0.0, math.pi]), [square(5.0, 0.0)])
    assert ranges[0, 0] == pytest.approx(4.5)
    assert ranges[1, 0] == math.inf


def test_each_polygon_gets_its_own_column_whatever_its_number_of_corners():
    triangle = np.array([[2.0, -1.0], [2.0, 1.0], [3.0, 0.0]])
    ranges = ray_polygon_ranges((0.0, 0.0), np.array([0.0, math.pi / 2]), [triangle, square(0.0, 10.0)])
    assert ranges.shape == (2, 2)
    assert ranges[0].tolist() == pytest.approx([2.0, math.inf])
    assert ranges[1].tolist() == pytest.approx([math.inf, 9.5])


def test_the_nearer_of_two_vehicles_in_line_hides_the_farther_one():
    ranges, hit = cast_rays((0.0, 0.0), np.array([0.0]), [square(20.0, 0.0), square(8.0, 0.0)], max_range_m=50.0)
    assert (ranges[0], hit[0]) == (pytest.approx(7.5), 1)


def test_a_hit_beyond_the_sensor_range_is_no_hit():
    ranges, hit = cast_rays((0.0, 0.0), np.array([0.0]), [square(20.0, 0.0)], max_range_m=10.0)
    assert (ranges[0], hit[0]) == (math.inf, -1)


def test_outlines_built_once_give_exactly_the_ranges_and_closest_points_of_the_polygons_themselves():
    rng = np.random.default_rng(7)
    polygons = [geometry.footprint_corners(*rng.uniform(-40.0, 40.0, 2), rng.uniform(-3.2, 3.2), 4.5, 1.8)
                for _ in range(9)]
    outlines = geometry.Outlines.of(polygons)
    azimuths = np.linspace(-1.5, 1.5, 181)
    assert np.array_equal(geometry.ray_polygon_ranges((1.0, 0.2), azimuths, outlines),
                          geometry.ray_polygon_ranges((1.0, 0.2), azimuths, polygons))
    nearest = outlines.closest_points((1.0, 0.2))
    for corners, edges, point in zip(outlines.corners, outlines.edges, nearest):
        assert np.array_equal(geometry.closest_point_on_polygon((1.0, 0.2), corners, edges), point)
        assert np.array_equal(geometry.closest_point_on_polygon((1.0, 0.2), corners), point)


def _nearest_on_outline_by_hand(point: tuple[float, float], corners: np.ndarray) -> tuple[float, float]:
    """Each edge's nearest point by the textbook projection, in plain floats; the nearest of them."""
    best = None
    for k in range(len(corners)):
        (ax, ay), (bx, by) = corners[k], corners[(k + 1) % len(corners)]
        ex, ey = bx - ax, by - ay
        u = min(max(((point[0] - ax) * ex + (point[1] - ay) * ey) / (ex * ex + ey * ey), 0.0), 1.0)
        candidate = (ax + u * ex, ay + u * ey)
        distance = math.hypot(candidate[0] - point[0], candidate[1] - point[1])
        if best is None or distance < best[0]:
            best = (distance, candidate)
    return best[1]


def test_the_closest_points_of_many_outlines_at_once_are_each_outlines_nearest_point_worked_out_by_hand():
    rng = np.random.default_rng(11)
    polygons = [geometry.footprint_corners(*rng.uniform(-40.0, 40.0, 2), rng.uniform(-3.2, 3.2), 4.5, 1.8)
                for _ in range(12)]
    for point in [tuple(rng.uniform(-40.0, 40.0, 2)) for _ in range(20)]:
        nearest = geometry.Outlines.of(polygons).closest_points(point)
        assert nearest.shape == (12, 2)
        for corners, found in zip(polygons, nearest):
            assert tuple(found) == pytest.approx(_nearest_on_outline_by_hand(point, corners), abs=1e-9)


def test_no_outlines_have_no_closest_points():
    assert geometry.Outlines.of([]).closest_points((0.0, 0.0)).shape == (0, 2)


def test_rays_cast_each_from_its_own_origin_meet_what_each_alone_meets():
    squares = [square(5.0, 0.0), square(0.0, 6.0), square(-4.0, -1.0)]
    origins = np.array([(0.0, 0.0), (0.0, 1.0), (-1.0, 2.0), (0.5, -0.5)])
    azimuths = np.array([0.0, math.pi / 2.0, -2.9, 0.3])
    together = ray_polygon_ranges(origins, azimuths, squares)
    for k, (origin, azimuth) in enumerate(zip(origins, azimuths)):
        assert np.array_equal(together[k], ray_polygon_ranges(tuple(origin), np.array([azimuth]), squares)[0])
    ranges, hit = cast_rays(origins, azimuths, squares, max_range_m=100.0)
    assert ranges[0] == pytest.approx(4.5) and hit[0] == 0
    assert ranges[1] == pytest.approx(4.5) and hit[1] == 1


@given(arrays(np.float64, array_shapes(min_dims=1, max_dims=3, max_side=6),
              elements=st.floats(allow_nan=False) | st.just(np.inf)))
def test_the_minimum_over_a_short_last_axis_is_numpys_minimum_to_the_bit(values):
    np.testing.assert_array_equal(geometry.min_over_last_axis(values), values.min(axis=-1))


@given(st.lists(st.tuples(st.floats(-30.0, 30.0), st.floats(-30.0, 30.0), st.floats(-3.2, 3.2),
                          st.floats(0.5, 18.0), st.floats(0.5, 3.0)), max_size=8),
       st.floats(-5.0, 5.0), st.floats(-5.0, 5.0), st.floats(0.0, 12.0))
def test_the_outlines_near_a_point_keep_every_outline_within_reach(vehicles, x_m, y_m, reach_m):
    outlines = geometry.Outlines.of([geometry.footprint_corners(*vehicle) for vehicle in vehicles])
    near = outlines.near((x_m, y_m), reach_m)
    within = np.hypot(*(outlines.closest_points((x_m, y_m)) - (x_m, y_m)).T) <= reach_m
    kept = {corners.tobytes() for corners in near.corners}
    assert all(corners.tobytes() in kept for corners in outlines.corners[within])


def test_rays_cast_at_the_outlines_near_their_origins_give_the_ranges_within_reach_of_all():
    rng = np.random.default_rng(5)
    polygons = [geometry.footprint_corners(*rng.uniform(-12.0, 12.0, 2), rng.uniform(-3.2, 3.2), 4.5, 1.8)
                for _ in range(10)]
    outlines = geometry.Outlines.of(polygons)
    origins = rng.uniform(-1.5, 1.5, (60, 2))
    azimuths = rng.uniform(-math.pi, math.pi, 60)
    reach_m = 4.0
    near = outlines.near((0.0, 0.0), reach_m + np.hypot(*origins.T).max())
    assert 0 < len(near) < len(outlines)
    assert np.array_equal(cast_rays(origins, azimuths, near, reach_m)[0],
                          cast_rays(origins, azimuths, outlines, reach_m)[0])
