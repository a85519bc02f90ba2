"""The ego lane from the map at the estimated position and the camera's lane markings."""

import math

import pytest

from coopdrive.services.scene.config import LaneFusionConfig
from coopdrive.services.scene.ego_lane import EgoLaneFusion, inverse_variance
from coopdrive.services.scene.frontends import LaneMarkings
from coopdrive.v1 import ego_pb2, scene_pb2, sensors_pb2

WIDTH_M = 3.5


def ego(offset_m: float, lane_index: int = 0, position_std_m: float = 0.02, heading_error_rad: float = 0.0,
        time_s: float = 1.0, speed_mps: float = 20.0) -> ego_pb2.EgoState:
    state = ego_pb2.EgoState(speed_mps=speed_mps, position_std_m=position_std_m)
    state.header.sample_time_s = time_s
    lane = state.lane
    lane.matched, lane.lane_index, lane.lateral_offset_m = True, lane_index, offset_m
    lane.heading_error_rad, lane.lane_width_m, lane.curvature_1pm = heading_error_rad, WIDTH_M, 0.001
    return state


def markings(offset_m: float, time_s: float = 1.0, heading_error_rad: float = 0.0, quality: float = 1.0,
             sides=(sensors_pb2.LANE_SIDE_LEFT, sensors_pb2.LANE_SIDE_RIGHT)) -> LaneMarkings:
    """What a camera sees with the rear axle offset_m left of the lane centre."""
    slope = -math.tan(heading_error_rad)
    lines = [sensors_pb2.LaneMarking(side=side, c0_m=-offset_m + sign * WIDTH_M / 2, c1=slope, c2_1pm=0.0005,
                                     quality=quality, view_range_m=40.0)
             for side, sign in ((sensors_pb2.LANE_SIDE_LEFT, 1.0), (sensors_pb2.LANE_SIDE_RIGHT, -1.0))
             if side in sides]
    return LaneMarkings(time_s=time_s, markings=tuple(lines))


def test_inverse_variance_weighting_is_the_textbook_minimum_variance_combination():
    value, std = inverse_variance(1.0, 1.0, 2.0, 2.0)
    assert value == pytest.approx((1.0 / 1 + 2.0 / 4) / (1 / 1 + 1 / 4))
    assert std == pytest.approx(math.sqrt(1 / (1 + 0.25)))


def test_without_markings_the_lane_is_the_map_s_with_the_position_s_uncertainty():
    lane = EgoLaneFusion().ego_lane(ego(0.3, lane_index=1, position_std_m=0.5), None, 1.0)
    assert lane.valid and lane.source == scene_pb2.LANE_SOURCE_MAP and lane.lane_index == 1
    assert lane.lateral_offset_m == pytest.approx(0.3)
    assert lane.lateral_offset_std_m == pytest.approx(math.hypot(0.5, LaneFusionConfig().map_offset_std_m))
    assert lane.left.c0_m == pytest.approx(-0.3 + WIDTH_M / 2) and lane.right.c0_m == pytest.approx(-0.3 - WIDTH_M / 2)


def test_a_camera_that_agrees_with_an_rtk_map_position_is_fused_close_to_the_map():
    lane = EgoLaneFusion().ego_lane(ego(0.20, position_std_m=0.02), markings(0.25), 1.0)
    assert lane.source == scene_pb2.LANE_SOURCE_FUSED and lane.lane_index == 0
    assert 0.20 < lane.lateral_offset_m < 0.25
    assert lane.lateral_offset_std_m < LaneFusionConfig().camera_offset_std_m
    assert lane.map_minus_camera_offset_m == pytest.approx(-0.05)


def test_a_gnss_error_that_moves_the_car_in_the_map_leaves_the_camera_alone_in_charge():
    fusion = EgoLaneFusion()
    fusion.ego_lane(ego(0.0), markings(0.0), 1.0)
    # GNSS now places the car 1.2 m left of where it is; the estimate still claims RTK precision
    lane = fusion.ego_lane(ego(1.2, time_s=1.1), markings(0.0, time_s=1.1), 1.1)
    assert lane.source == scene_pb2.LANE_SOURCE_CAMERA and lane.lane_index == 0
    assert lane.lateral_offset_m == pytest.approx(0.0)
    assert lane.map_minus_camera_offset_m == pytest.approx(1.2)
    assert fusion.disagreements == 1


def test_a_map_a_whole_lane_off_keeps_the_camera_s_lane_counted_from_where_they_agreed():
    fusion = EgoLaneFusion()
    fusion.ego_lane(ego(0.1, lane_index=0), markings(0.1), 1.0)
    # the estimate jumps a lane to the left: map says lane 1 near its centre, the camera still sees lane 0
    lane = fusion.ego_lane(ego(0.2, lane_index=1, time_s=1.1), markings(0.1, time_s=1.1), 1.1)
    assert lane.lane_index == 0 and lane.source == scene_pb2.LANE_SOURCE_CAMERA
    assert lane.map_minus_camera_offset_m == pytest.approx(0.2 + WIDTH_M - 0.1)


def test_the_camera_counts_a_lane_change_by_the_line_the_car_crosses():
    fusion = EgoLaneFusion()
    fusion.ego_lane(ego(1.6, lane_index=0), markings(1.6), 1.0)
    # across the left line: the camera now sees lane 1's lines, 1.8 m to the right of its centre
    lane = fusion.ego_lane(ego(-1.8, lane_index=1, time_s=1.1), markings(-1.8, time_s=1.1), 1.1)
    assert lane.lane_index == 1 and lane.source == scene_pb2.LANE_SOURCE_FUSED
    assert lane.lateral_offset_m == pytest.approx(-1.8)


def test_one_marking_with_the_map_s_width_is_enough_and_a_poor_one_is_not_used():
    lane = EgoLaneFusion().ego_lane(ego(0.0, position_std_m=2.0), markings(0.4, sides=(sensors_pb2.LANE_SIDE_RIGHT,)),
                                    1.0)
    assert lane.source == scene_pb2.LANE_SOURCE_FUSED and lane.lateral_offset_m == pytest.approx(0.4, abs=0.01)
    poor = EgoLaneFusion().ego_lane(ego(0.0), markings(0.4, quality=0.1), 1.0)
    assert poor.source == scene_pb2.LANE_SOURCE_MAP


def test_stale_markings_are_not_used_and_fresh_ones_are_moved_on_along_the_heading_error():
    fusion = EgoLaneFusion()
    stale = fusion.ego_lane(ego(0.0, time_s=2.0), markings(0.0, time_s=1.0), 2.0)
    assert stale.source == scene_pb2.LANE_SOURCE_MAP
    heading_error_rad = 0.02
    moved = EgoLaneFusion().ego_lane(ego(0.0, position_std_m=5.0, heading_error_rad=heading_error_rad, time_s=1.1),
                                     markings(0.0, time_s=1.0, heading_error_rad=heading_error_rad), 1.1)
    # 20 m/s for 0.1 s at 0.02 rad: 4 cm further left
    assert moved.lateral_offset_m == pytest.approx(20.0 * math.sin(heading_error_rad) * 0.1, abs=0.005)
    assert moved.heading_error_rad == pytest.approx(heading_error_rad, abs=1e-3)


def test_markings_without_a_map_lane_give_no_lane_until_the_camera_s_lane_is_known():
    fusion = EgoLaneFusion()
    unmatched = ego(0.0)
    unmatched.lane.matched = False
    assert not fusion.ego_lane(unmatched, markings(0.0), 1.0).valid
    fusion.ego_lane(ego(0.0), markings(0.0, time_s=1.1), 1.1)
    lane = fusion.ego_lane(unmatched, markings(0.3, time_s=1.2), 1.2)
    assert lane.valid and lane.source == scene_pb2.LANE_SOURCE_CAMERA and lane.lateral_offset_m == pytest.approx(0.3)


def test_no_ego_state_gives_no_lane():
    assert not EgoLaneFusion().ego_lane(None, markings(0.0), 1.0).valid
