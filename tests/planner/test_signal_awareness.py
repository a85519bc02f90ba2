"""Signal awareness alone (services/planner/signals/), fed protobufs by hand: the MAP's lanes in metres about the
reference point, the lane and signal group matched, TimeMarks on the stack clock, SPaT stale or contradicting."""

from __future__ import annotations

import math

import pytest
from signal_world import GREEN, LEFT, RED, RIGHT, STRAIGHT, ego_at, event, light, mapem, spatem

from coopdrive.services.planner.config import Intention, SignalConfig
from coopdrive.services.planner.signals.awareness import SignalAwareness, SignalStatus
from coopdrive.roadmap.intersection_lanes import reference_plane
from coopdrive.services.planner.signals.lanes import ingress_lanes
from coopdrive.services.planner.signals.time_mark import stack_time_of_mark_s
from coopdrive.v2x.timebase import ItsClock

HOUR_S = 3600.0


def aware(map_content=None) -> SignalAwareness:
    awareness = SignalAwareness(SignalConfig(), ItsClock())
    awareness.on_mapem(map_content or mapem())
    return awareness


def view(awareness: SignalAwareness, now_s: float, x_m: float, intention=Intention.STRAIGHT, **ego):
    e = ego_at(x_m, **ego)
    return awareness.view(now_s, e.latitude_deg, e.longitude_deg, e.heading_rad, intention)


def test_the_first_node_is_the_stop_line_and_each_later_node_is_an_offset_from_the_one_before():
    intersection = mapem().intersections[0]
    (lane,) = ingress_lanes(intersection, reference_plane(intersection))
    assert lane.nodes == ((-10.0, -1.75), (-110.0, -1.75), (-310.0, -1.75))
    assert lane.stop_line == (-10.0, -1.75) and lane.heading_at_stop_line_rad() == pytest.approx(0.0)


@pytest.mark.parametrize("intention, group", [(Intention.STRAIGHT, STRAIGHT), (Intention.LEFT, LEFT),
                                              (Intention.RIGHT, RIGHT)])
def test_the_ego_on_the_ingress_lane_obeys_the_signal_group_of_its_movement(intention, group):
    awareness = aware()
    awareness.on_spatem(spatem([event(GREEN, likely_s=30.0)], group=group), 0.0)
    seen = view(awareness, 0.1, -100.0, intention)
    assert (seen.status, seen.signal_group, seen.match.lane.lane_id) == (SignalStatus.OK, group, 1)
    assert seen.match.to_stop_line_m == pytest.approx(90.0, abs=0.01)


def test_the_ego_in_the_box_is_still_on_its_lane_past_the_stop_line_and_off_it_beyond_the_box():
    awareness = aware()
    assert view(awareness, 0.0, 0.0).match.to_stop_line_m == pytest.approx(-10.0, abs=0.01)
    assert view(awareness, 0.0, 31.0).status is SignalStatus.NO_LANE


def test_the_ego_off_every_ingress_lane_is_matched_to_no_lane_rather_than_the_nearest():
    awareness = aware()
    assert view(awareness, 0.0, -100.0, y_m=2.6).status is SignalStatus.NO_LANE  # half a lane + 0.5 m is 2.25 m
    assert view(awareness, 0.0, -100.0, heading_rad=math.radians(31.0)).status is SignalStatus.NO_LANE
    assert view(awareness, 0.0, -320.0).status is SignalStatus.NO_LANE  # beyond the MAP's last node
    assert view(aware(mapem(lane_shift_m=4.0)), 0.0, -100.0).status is SignalStatus.NO_LANE


def test_a_lane_without_a_movement_of_the_intended_turn_has_no_signal_group():
    content = mapem()
    del content.intersections[0].lanes[0].connections[1]
    seen = view(aware(content), 0.0, -100.0, Intention.LEFT)
    assert seen.status is SignalStatus.NO_GROUP and "LEFT" in seen.why


def test_no_map_and_no_spat_are_named():
    assert SignalAwareness(SignalConfig(), ItsClock()).view(0.0, 50.0, 5.0, 0.0).status is SignalStatus.NO_MAP
    assert view(aware(), 0.0, -100.0).status is SignalStatus.NO_SPAT


def test_spat_older_than_the_stale_limit_is_stale():
    awareness = aware()
    awareness.on_spatem(light((RED, 30.0)), 10.0)
    assert view(awareness, 11.0, -100.0).status is SignalStatus.OK
    assert view(awareness, 11.05, -100.0).status is SignalStatus.STALE


def test_a_roadside_unit_at_0_5_hz_is_judged_at_its_own_pace_so_its_spat_is_stale_only_after_three_of_its_gaps():
    awareness, config = aware(), SignalConfig()
    for k in range(4):  # a SPATEM every 2 s
        awareness.on_spatem(light((RED, 60.0)), 2.0 * k)
    last_s = 6.0
    # One SPATEM lost (a 4 s gap) is not stale; three periods (6 s) are capped at spat_stale_max_s.
    assert view(awareness, last_s + 4.0, -100.0).status is SignalStatus.OK
    assert view(awareness, last_s + config.spat_stale_max_s, -100.0).status is SignalStatus.OK
    assert view(awareness, last_s + config.spat_stale_max_s + 0.05, -100.0).status is SignalStatus.STALE


def test_a_roadside_unit_at_10_hz_is_stale_after_one_second_as_the_fixed_limit_says():
    awareness = aware()
    for k in range(11):
        awareness.on_spatem(light((RED, 60.0)), 0.1 * k)
    assert view(awareness, 2.0, -100.0).status is SignalStatus.OK
    assert view(awareness, 2.05, -100.0).status is SignalStatus.STALE


@pytest.mark.parametrize("period_s, stale_after_s", [(None, 1.0), (0.1, 1.0), (0.5, 1.5), (1.0, 3.0), (2.0, 5.0)])
def test_the_stale_limit_is_three_of_the_intersections_gaps_between_one_and_five_seconds(period_s, stale_after_s):
    assert SignalConfig().stale_after_s(period_s) == pytest.approx(stale_after_s)


def test_a_stale_cap_below_the_stale_floor_is_refused_naming_both():
    with pytest.raises(ValueError, match="spat_stale_max_s 0.5 is below spat_stale_s 1"):
        SignalConfig(spat_stale_max_s=0.5)


def test_a_contradiction_is_held_for_its_hold_time_then_forgotten():
    awareness = aware()
    awareness.on_spatem(spatem([event(RED, 20.0, 25.0, 30.0)]), 0.0)
    awareness.on_spatem(spatem([event(RED, 10.0, 25.0, 30.0)]), 0.1)
    assert view(awareness, 0.2, -100.0).why.endswith("minEndTime jumped back")
    for k in range(1, 60):
        awareness.on_spatem(spatem([event(RED, 10.0, 25.0, 30.0)]), 0.1 + 0.1 * k)
    assert view(awareness, 6.0, -100.0).status is SignalStatus.OK


@pytest.mark.parametrize("unix_now_s, mark_s, expected_s", [
    (10 * HOUR_S + 100.0, 130.5, 30.5),           # within the hour
    (10 * HOUR_S + 3599.5, 0.5, 1.0),             # a mark past the hour, read just before it
    (10 * HOUR_S + 0.3, 3599.8, -0.5),            # a mark just before the hour, read just after it
    (10 * HOUR_S + 1800.0, 3600.0, 1800.0),       # a leap second's last tenth
])
def test_a_time_mark_is_placed_in_the_hour_nearest_the_receivers_utc(unix_now_s, mark_s, expected_s):
    clock = ItsClock(epoch_unix_s=unix_now_s - 5.0)  # the stack clock reads 5 s at unix_now_s
    assert stack_time_of_mark_s(mark_s, 5.0, clock) - 5.0 == pytest.approx(expected_s)
