import math

import pytest
from drivers import fired
from intersection_drivers import (
    APPROACH, COMPETITOR, CROSSING, DRIVERS, GIVE_WAY, HOLD_SAFE, ORGANISER, cross_planner, world)
from planner_world import iclcm, obj

from coopdrive.services.planner.speed_profile import QuinticArrival
from coopdrive.v1 import planner_pb2

NORTH = math.pi / 2


def test_the_quintic_profile_arrives_at_the_point_on_time_at_the_speed_without_acceleration():
    profile = QuinticArrival.plan(200.0, 20.0, 15.0, 0.5, 30 / 3.6)
    assert profile.position_m(20.0) == pytest.approx(200.0)
    assert profile.speed_mps(0.0) == pytest.approx(15.0)
    assert profile.accel_mps2(0.0) == pytest.approx(0.5)
    assert profile.speed_mps(20.0 - 1e-9) == pytest.approx(30 / 3.6)
    assert profile.accel_mps2(20.0 - 1e-9) == pytest.approx(0.0, abs=1e-6)
    assert QuinticArrival.plan(200.0, 0.0, 15.0, 0.0, 8.0) is None


def test_the_vehicle_approaches_on_the_arrival_profile_gives_way_to_the_organiser_then_crosses_and_exits():
    p = cross_planner()
    _, state = p.step(0.0, world(0.0, -300.0, start=False))
    assert state.state == "IDLE"
    request, state = p.step(0.1, world(0.1, -300.0))
    assert state.state == "APPROACH" and request.has_arrival
    assert request.arrival_time_s == 20.0 and request.arrival_speed_mps == pytest.approx(30 / 3.6)
    assert 0 < request.desired_speed_mps < 50 / 3.6
    request, state = p.step(0.2, world(0.2, -90.0, organiser_y_m=-50.0))
    assert state.state == "GIVE_WAY"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(75.0)
    assert [t.station_id for t in request.targets if t.role == planner_pb2.TARGET_ROLE_YIELD] == [ORGANISER]
    request, state = p.step(0.3, world(0.3, -80.0, organiser_y_m=30.0))
    assert state.state == "CROSSING" and request.desired_speed_mps == pytest.approx(50 / 3.6)
    request, state = p.step(1.3, world(1.3, 20.0))
    assert state.state == "EXITED"
    assert request.iclcm.counter_intersection == 1 and request.iclcm.intention == 1
    assert request.iclcm.distance_travelled_cz_m == pytest.approx(8.0 * 1.2)


def test_a_clear_competition_zone_is_crossed_without_stopping():
    p, _ = APPROACH.run()
    _, state = p.step(0.1, world(0.1, -95.0))
    assert state.state == "CROSSING"


def test_a_competitor_further_into_the_zone_has_priority():
    p, _ = APPROACH.run()
    rival = obj(8, COMPETITOR, gap_m=90.0, x_m=0.0, y_m=-20.0, heading_rad=NORTH)
    msgs = {COMPETITOR: iclcm(COMPETITOR, 0.1, distance_travelled_cz_m=80.0)}
    _, state = p.step(0.1, world(0.1, -95.0, extra=[rival], msgs=msgs))
    assert state.state == "GIVE_WAY"


def test_giving_way_escapes_to_hold_after_its_timeout_and_holds_at_the_stop_line():
    p, _ = GIVE_WAY.run()
    request, state = p.step(30.1, world(30.1, -20.0, organiser_y_m=-40.0))
    assert state.state == "HOLD_SAFE" and state.recent_transitions[-1].event == "TIMEOUT"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(5.0)


def test_an_organiser_heard_but_never_seen_is_a_contradiction_and_the_scene_decides():
    p, _ = APPROACH.run()
    _, state = p.step(0.1, world(0.1, -90.0, organiser_heard=True))
    assert state.state == "GIVE_WAY"
    _, state = p.step(2.1, world(2.1, -80.0, organiser_heard=True))
    hold, cross = state.recent_transitions[-2:]
    assert (hold.to_state, hold.event) == ("HOLD_SAFE", "SCENE_CONTRADICTS_V2V")
    assert (cross.to_state, cross.event) == ("CROSSING", "PATH_CLEAR_BY_SCENE")
    assert state.state == "CROSSING"


def test_an_approach_that_never_reaches_the_zone_escapes_to_hold():
    p, _ = APPROACH.run()
    _, state = p.step(120.0, world(120.0, -300.0))
    assert state.state == "HOLD_SAFE"


def test_crossing_keeps_the_safety_circle_and_escapes_to_hold_when_it_never_ends():
    p, _ = CROSSING.run()
    close = obj(6, 0, gap_m=5.0, x_m=-5.0, y_m=0.0, speed_mps=0.0)
    request, state = p.step(0.2, world(0.2, -10.0, extra=[close]))
    assert state.state == "CROSSING" and request.desired_speed_mps == 0.0
    assert request.targets[0].role == planner_pb2.TARGET_ROLE_YIELD and request.targets[0].extra_gap_m == 7.5
    _, state = p.step(30.1, world(30.1, -10.0, extra=[close]))
    assert state.state == "HOLD_SAFE"


def test_a_priority_vehicle_appearing_before_the_stop_line_makes_a_crossing_vehicle_hold_at_the_line():
    p, _ = CROSSING.run()
    request, state = p.step(0.2, world(0.2, -60.0, organiser_y_m=-40.0))
    assert state.state == "HOLD_SAFE" and request.has_stop_line


def test_without_an_arrival_time_the_approach_holds_the_arrival_speed():
    p = cross_planner(arrival_time_s=0.0)
    p.step(0.0, world(0.0, -300.0))
    request, state = p.step(0.1, world(0.1, -300.0))
    assert state.state == "APPROACH" and not request.has_arrival
    assert request.desired_speed_mps == pytest.approx(30 / 3.6)


def test_an_organiser_standing_at_its_stop_line_outside_the_safety_circle_lets_the_vehicle_cross():
    p = cross_planner()
    p.step(0.0, world(0.0, -90.0, organiser_y_m=-30.0))
    _, state = p.step(0.1, world(0.1, -90.0, organiser_y_m=-30.0))
    assert state.state == "GIVE_WAY"
    _, state = p.step(0.2, world(0.2, -80.0, organiser_y_m=-12.0, organiser_speed_mps=0.2))
    assert state.state == "CROSSING"


def test_a_car_passing_the_other_way_in_its_own_lane_is_no_reason_to_stop_while_crossing():
    p, _ = CROSSING.run()
    oncoming = obj(6, 0, gap_m=3.0, x_m=-7.0, y_m=3.5, speed_mps=8.0, heading_rad=math.pi)
    request, state = p.step(0.2, world(0.2, -10.0, extra=[oncoming]))
    assert state.state == "CROSSING" and request.desired_speed_mps == pytest.approx(50 / 3.6)
    assert not any(t.role == planner_pb2.TARGET_ROLE_YIELD for t in request.targets)


@pytest.mark.parametrize("heading_std_rad, stops", [(0.0, True), (0.05, True), (0.3, False)])
def test_a_car_seen_crossing_our_path_stops_us_unless_its_heading_s_uncertainty_leaves_it_in_its_own_lane(
        heading_std_rad, stops):
    """A new track on a car passing the other way has a heading out of a few positions: 60 degrees off its lane
    give or take 0.3 rad may be a car in its own lane, give or take 0.05 rad it is not."""
    p, _ = CROSSING.run()
    # The ego heads east at x = -10 m; this car, 3 m ahead and 2 m to our right, heads 60 degrees off west,
    # towards our path.
    turning = obj(6, 0, gap_m=3.0, x_m=-7.0, y_m=-2.0, speed_mps=8.0, heading_rad=math.radians(120.0))
    turning.heading_rad.std = heading_std_rad
    request, state = p.step(0.2, world(0.2, -10.0, extra=[turning]))
    assert state.state == "CROSSING"
    assert (request.desired_speed_mps == 0.0) is stops
    assert any(t.role == planner_pb2.TARGET_ROLE_YIELD for t in request.targets) is stops


@pytest.mark.parametrize("length_m, stops", [(4.5, True), (1.0, False)])
def test_the_safety_circle_holds_a_car_whose_front_is_inside_it_though_its_rear_is_not(length_m, stops):
    """The scene places a car at its rear bumper; coming towards our path, its front is nearest us."""
    p, _ = CROSSING.run()
    # The ego at x = -10 m heads east; this car's rear is 8.9 m away, 4 m ahead and 8 m to our right, and it heads
    # north across our path: its front, 4.5 m on, is 5.3 m from us.
    crossing = obj(6, 0, gap_m=4.0, x_m=-6.0, y_m=-8.0, speed_mps=8.0, heading_rad=NORTH)
    crossing.length_m.value, crossing.length_m.confidence = length_m, 1.0
    request, state = p.step(0.2, world(0.2, -10.0, extra=[crossing]))
    assert state.state == "CROSSING"
    assert (request.desired_speed_mps == 0.0) is stops


def test_a_sonar_echo_at_our_side_whose_speed_is_unknown_is_no_reason_to_stop_while_crossing():
    """A side sonar's echo off a car passing the other way is an object with no speed, 1.4 m ahead and 2.7 m to
    our left (intersection seed 7): taken for a standing car, it braked us at 6 m/s2."""
    p, _ = CROSSING.run()
    echo = obj(6, 0, gap_m=1.4, x_m=-6.6, y_m=2.7, speed_mps=0.0)
    echo.speed_mps.confidence = echo.heading_rad.confidence = -1.0
    request, state = p.step(0.2, world(0.2, -10.0, extra=[echo]))
    assert state.state == "CROSSING" and request.desired_speed_mps == pytest.approx(50 / 3.6)
    assert not any(t.role == planner_pb2.TARGET_ROLE_YIELD for t in request.targets)


def test_a_competitor_further_into_the_zone_on_our_own_road_is_no_conflict_when_going_straight():
    competitor = obj(6, COMPETITOR, gap_m=40.0, x_m=40.0, y_m=3.5, speed_mps=8.0, heading_rad=math.pi)
    ahead_in_zone = {COMPETITOR: iclcm(COMPETITOR, 0.2, distance_travelled_cz_m=80.0)}
    p, _ = CROSSING.run()
    _, state = p.step(0.2, world(0.2, -90.0, extra=[competitor], msgs=ahead_in_zone))
    assert state.state == "CROSSING"


@pytest.mark.parametrize("source", ["IDLE", "APPROACH", "HOLD_SAFE"])
def test_the_rsu_end_of_scenario_ends_the_scenario_before_the_box_without_counting_a_crossing(source):
    request, state = DRIVERS[("intersection", source, "END_OF_SCENARIO", "EXITED")]()
    assert state.state == "EXITED"
    assert fired(state, source, "END_OF_SCENARIO", "EXITED").reason == "RSU endOfScenario"
    assert request.iclcm.counter_intersection == 0


def test_a_vehicle_held_before_the_stop_line_when_the_scenario_ends_still_gives_way_until_the_organiser_passed():
    request, state = DRIVERS[("intersection", "HOLD_SAFE", "END_OF_SCENARIO", "EXITED")]()
    assert state.state == "EXITED"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(45.0)
    assert [t.station_id for t in request.targets if t.role == planner_pb2.TARGET_ROLE_YIELD] == [ORGANISER]
    p, _ = HOLD_SAFE.run()
    HOLD_SAFE.step(p, 0.3, end=True)
    request, state = HOLD_SAFE.step(p, 0.4, end=True, organiser_y_m=30.0)
    assert state.state == "EXITED" and not request.has_stop_line
    assert request.desired_speed_mps == pytest.approx(50 / 3.6)


def test_after_the_scenario_ended_an_organiser_heard_but_never_seen_does_not_hold_the_vehicle_for_ever():
    p, _ = HOLD_SAFE.run()
    HOLD_SAFE.step(p, 0.3, end=True)
    request, state = HOLD_SAFE.step(p, 0.4, end=True, organiser_y_m=None, organiser_heard=True)
    assert state.state == "EXITED" and not request.has_stop_line
