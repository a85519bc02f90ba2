"""A projection that looks only at the segments NearSegments names finds what the pass over every segment finds,
to the bit, near every lane of the shipped maps and where a line folds back on itself."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.roadmap import Lane, RoadMap
from coopdrive.roadmap.near_segments import CELL_M, MAX_CANDIDATES

SHIPPED_MAPS = ("a270", "intersection")


def points_near(lane: Lane, count: int, rng: np.random.Generator) -> list[tuple[float, float]]:
    """Points up to 12 m either side of the centre line, from 20 m before its start to 20 m past its end."""
    stations = rng.uniform(-20.0, lane.length_m + 20.0, count)
    offsets = rng.uniform(-12.0, 12.0, count)
    return [lane.pose_at(station, offset)[:2] for station, offset in zip(stations, offsets)]


@pytest.mark.parametrize("map_name", SHIPPED_MAPS)
def test_near_every_lane_of_a_shipped_map_the_few_candidates_give_the_nearest_segment_of_all(map_name):
    rng = np.random.default_rng(7)
    looked_at_few = 0
    for lane in RoadMap.load(map_name).lanes:
        for x_m, y_m in points_near(lane, 400, rng):
            candidates = lane._near.candidates(x_m, y_m)
            if candidates is None:
                continue
            looked_at_few += 1
            assert lane._nearest_of(candidates, x_m, y_m) == lane._nearest_of_all(x_m, y_m), (lane.lane_id, x_m, y_m)
    assert looked_at_few > 0


def hairpin() -> Lane:
    """Out 60 m east, a tight turn, back west 4 m to the north of the way out."""
    turn = [(60.0 + 2.0 * math.sin(a), 2.0 - 2.0 * math.cos(a)) for a in np.linspace(0.0, math.pi, 9)]
    return Lane("hairpin/0", "hairpin", 0, 3.5, np.array([(0.0, 0.0), *turn, (0.0, 4.0)]))


@settings(max_examples=300, deadline=None)
@given(x_m=st.floats(-10.0, 75.0), y_m=st.floats(-8.0, 12.0))
def test_where_the_line_folds_back_the_projection_is_the_full_pass_s(x_m, y_m):
    lane = hairpin()
    candidates = lane._near.candidates(x_m, y_m)
    if candidates is not None:
        assert lane._nearest_of(candidates, x_m, y_m) == lane._nearest_of_all(x_m, y_m)


def test_far_from_a_long_line_too_many_segments_qualify_and_the_full_pass_is_used():
    # A line of 3 m segments: seen from 50 m away, the segments within two half-diagonals of a cell of the nearest
    # one's distance span some 56 m.
    lane = Lane("long/0", "long", 0, 3.5, np.column_stack((np.arange(0.0, 201.0, 3.0), np.zeros(67))))
    assert len(lane._near.candidates(100.0, 1.0)) <= MAX_CANDIDATES
    assert lane._near.candidates(100.0, 50.0) is None
    assert lane.project(100.0, 50.0)[:2] == pytest.approx((100.0, 50.0))


def test_a_cell_is_worked_out_once_and_its_points_share_it():
    lane = hairpin()
    first = lane._near.candidates(30.1, 0.4)
    assert lane._near.candidates(30.1 + 0.5 * CELL_M - 0.2, 0.4) is first
