"""The planner at a signalised stop line (the traffic lights' machine beside the scenario's), from decoded MAPEMs
and SPATEMs: what it asks of control on red, amber and green, with and without GLOSA, and on SPaT it cannot use.
A point-mass ego driven by its requests checks the claims over whole approaches."""

from __future__ import annotations

import math

import pytest
from planner_world import inputs, obj, scene
from signal_world import (AMBER, GREEN, LANE_Y_M, RED, RED_AMBER, STOP_LINE_X_M, ego_at, event, fixed_time, heard,
                          light, mapem, spatem)

from coopdrive.services.planner.config import PlannerLogicConfig
from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import planner_pb2

LIMIT_MPS = 13.9
FRONT_M = PlannerLogicConfig().signals.rear_axle_to_front_m
DT_S = 0.1
# The point-mass ego: reaches its requested speed at these rates, brakes for a stop line on the curve sqrt(2 b d).
ACCEL_MPS2, BRAKE_MPS2, STOP_CURVE_MPS2 = 2.0, 6.0, 3.0


def planner(glosa: bool = True) -> Planner:
    return Planner(PlannerLogicConfig(cruise_speed_mps=LIMIT_MPS), glosa=glosa)


def step(p: Planner, t: float, x_m: float, spat, speed_mps: float = LIMIT_MPS, spat_at_s: float | None = None,
         **ego) -> planner_pb2.BehaviourRequest:
    spatems = heard(spat, t if spat_at_s is None else spat_at_s)
    request, _ = p.step(t, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(x_m, speed_mps, **ego),
                                  mapems=heard(mapem(), 0.0), spatems=spatems))
    return request


def front_to_line_m(x_m: float) -> float:
    return STOP_LINE_X_M - (x_m + FRONT_M)


def test_the_ego_stops_at_the_stop_line_on_red_when_it_can():
    p = planner(glosa=False)
    request = step(p, 0.0, -180.0, light((RED, 60.0), (GREEN, 90.0)))
    assert p.lights_machine.state.name == "STOP"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(front_to_line_m(-180.0), abs=0.05)


def test_the_ego_proceeds_on_amber_when_it_cannot_stop_within_the_comfort_deceleration():
    # 13.9 m/s: 0.5 s reaction and 3 m/s2 take 39.2 m; the line is 16.2 m ahead.
    p = planner()
    request = step(p, 0.0, -30.0, light((AMBER, 3.0), (RED, 30.0)))
    assert p.lights_machine.state.name == "COMMITTED" and not request.has_stop_line
    assert request.desired_speed_mps == LIMIT_MPS


def test_on_amber_ending_before_the_ego_could_reach_the_line_it_stops_even_beyond_comfort():
    # 16.2 m at 13.9 m/s is 1.17 s; the amber ends in 1.0 s.
    p = planner()
    request = step(p, 0.0, -30.0, light((AMBER, 1.0), (RED, 30.0)))
    assert p.lights_machine.state.name == "STOP" and request.has_stop_line


def test_the_ego_stops_on_amber_when_the_line_is_beyond_the_comfortable_stopping_distance():
    p = planner()
    request = step(p, 0.0, -80.0, light((AMBER, 3.0), (RED, 30.0)))
    assert p.lights_machine.state.name == "STOP" and request.has_stop_line


def test_glosa_slows_to_arrive_on_green_and_never_exceeds_the_limit():
    p = planner()
    request = step(p, 0.0, -180.0, light((RED, 15.0), (GREEN, 45.0)))
    # 166.2 m to the line, green at 15 s plus the 1 s margin: 10.4 m/s, and the stop line while it is red.
    assert p.lights_machine.state.name == "GLOSA"
    assert request.desired_speed_mps == pytest.approx(front_to_line_m(-180.0) / 16.0, rel=1e-3)
    assert request.has_stop_line
    for green_s in (1.0, 5.0, 12.0, 20.0, 28.0):
        speed = step(planner(), 0.0, -180.0, light((RED, green_s), (GREEN, green_s + 30.0))).desired_speed_mps
        assert PlannerLogicConfig().signals.glosa_min_speed_mps <= speed <= LIMIT_MPS


def test_glosa_holds_on_when_the_green_is_due_but_its_spatem_has_not_come_yet():
    # The SPaT heard at 29.95 s said red-amber until 30.0 s, then green; at 30.0 s the ego still slows for it.
    p = planner()
    step(p, 29.9, -180.0, light((RED_AMBER, 30.0), (GREEN, 60.0)))
    request = step(p, 30.0, -178.6, light((RED_AMBER, 30.0), (GREEN, 60.0)), spat_at_s=29.95)
    # Not a stop: GLOSA at the limit (the green is on by the time it arrives), the stop line kept until it is.
    assert p.lights_machine.state.name == "GLOSA" and request.has_stop_line
    assert request.desired_speed_mps == pytest.approx(LIMIT_MPS)


def test_without_glosa_the_ego_keeps_the_limit_and_stops_on_red():
    p = planner(glosa=False)
    request = step(p, 0.0, -180.0, light((RED, 15.0), (GREEN, 45.0)))
    assert p.lights_machine.state.name == "STOP"
    assert request.desired_speed_mps == LIMIT_MPS and request.has_stop_line


def test_a_green_lasting_until_the_ego_arrives_adds_nothing_to_the_scenarios_request():
    p = planner()
    request = step(p, 0.0, -180.0, light((GREEN, 60.0)))
    assert p.lights_machine.state.name == "GO"
    assert not request.has_stop_line and request.desired_speed_mps == LIMIT_MPS


def test_the_ego_waits_at_the_line_on_green_while_the_queue_ahead_leaves_no_room_past_the_box():
    p = planner()
    queue = scene(obj(7, gap_m=60.0, speed_mps=0.0), forward_mio=7)
    request, _ = p.step(0.0, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(-60.0), scene=queue,
                                    mapems=heard(mapem(), 0.0), spatems=heard(light((GREEN, 60.0)), 0.0)))
    # 46.2 m to the line, the queue's end 13.8 m past it: less than the 25 m it takes to leave the box.
    assert p.lights_machine.state.name == "STOP" and request.has_stop_line
    moving = scene(obj(7, gap_m=60.0, speed_mps=3.0), forward_mio=7)
    request, _ = p.step(0.1, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(-58.6), scene=moving,
                                    mapems=heard(mapem(), 0.0), spatems=heard(light((GREEN, 60.0)), 0.1)))
    assert p.lights_machine.state.name == "GO" and not request.has_stop_line


def test_stale_spat_brings_a_safe_stop_at_the_stop_line():
    p = planner()
    step(p, 0.0, -180.0, light((GREEN, 60.0)))
    request = step(p, 1.5, -160.0, light((GREEN, 60.0)), spat_at_s=0.0)
    assert p.lights_machine.state.name == "SAFE_STOP" and "old" in p.lights.view.why
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(front_to_line_m(-160.0), abs=0.05)


@pytest.mark.parametrize("first, then, why", [
    ([event(GREEN, 10.0, 12.0, 9.0)], None, "minEndTime after maxEndTime"),
    ([event(RED, 20.0, 25.0, 30.0)], [event(RED, 12.0, 15.0, 30.0)], "minEndTime jumped back"),
    ([event(RED, 20.0, 25.0, 30.0)], [event(GREEN, 40.0, 45.0, 50.0)], "phase ended before its minEndTime"),
])
def test_spat_contradicting_itself_brings_a_safe_stop(first, then, why):
    p = planner()
    step(p, 0.0, -180.0, spatem(first))
    step(p, 0.1, -178.6, spatem(then or first))
    assert p.lights_machine.state.name == "SAFE_STOP" and p.lights.view.why.endswith(why)


def test_the_ego_off_every_ingress_lane_is_matched_to_none():
    for ego in ({"y_m": LANE_Y_M + 3.0}, {"heading_rad": math.pi}, {"heading_rad": math.radians(40.0)}):
        p = planner()
        step(p, 0.0, -180.0, light((RED, 60.0), (GREEN, 90.0)), **ego)
        assert p.lights.view.status.name == "NO_LANE"


def test_going_another_way_than_every_signalised_lane_the_scenario_drives_on():
    for heading_deg in (180.0, 40.0):
        p = planner()
        request = step(p, 0.0, -180.0, light((RED, 60.0), (GREEN, 90.0)), heading_rad=math.radians(heading_deg))
        assert p.lights_machine.state.name == "IDLE" and not request.has_stop_line


def test_a_map_whose_lane_misses_the_egos_path_brings_a_safe_stop_at_its_stop_line():
    p = planner()
    request, _ = p.step(0.0, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(-180.0), mapems=heard(mapem(4.0), 0.0),
                                    spatems=heard(light((GREEN, 60.0)), 0.0)))
    assert p.lights.view.status.name == "NO_LANE" and p.lights_machine.state.name == "SAFE_STOP"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(front_to_line_m(-180.0), abs=0.05)


def drive(p: Planner, plan, x_m: float = -300.0, duration_s: float = 50.0) -> list[tuple[float, float, int]]:
    """The point-mass ego through the intersection under a fixed-time plan(t): (t, front to line, light) a step."""
    speed, trace = LIMIT_MPS, []
    for k in range(int(duration_s / DT_S)):
        t = k * DT_S
        phases = plan(t)
        request = step(p, t, x_m, light(*phases), speed_mps=speed)
        target = request.desired_speed_mps
        if request.has_stop_line:
            target = min(target, math.sqrt(2.0 * STOP_CURVE_MPS2 * max(request.stop_line_distance_m - 1.0, 0.0)))
        speed = max(0.0, speed + min(max(target - speed, -BRAKE_MPS2 * DT_S), ACCEL_MPS2 * DT_S))
        trace.append((t, front_to_line_m(x_m), phases[0][0]))
        x_m += speed * DT_S
    return trace


def entered_on(trace) -> int | None:
    """The light when the front bumper crossed the stop line, None if it never did."""
    return next((light for (_, before, _), (_, after, light) in zip(trace, trace[1:]) if before >= 0 > after), None)


# Arriving (at the limit, 20.6 s) in the green, at its end, in the amber, in the red, at its end.
PLANS = [(10.0, 15.0), (20.0, 0.0), (10.0, 9.0), (10.0, 0.0), (10.0, 22.0)]


@pytest.mark.parametrize("glosa", [True, False])
@pytest.mark.parametrize("green_s, offset_s", PLANS)
def test_the_ego_never_enters_on_red(glosa, green_s, offset_s):
    trace = drive(planner(glosa), lambda t: fixed_time(t, green_s, 3.0, 20.0, offset_s))
    assert entered_on(trace) in (GREEN, AMBER)


def stops(trace) -> int:
    """Times the ego came to a standstill before the line."""
    speeds = [(before - after) / DT_S for (_, before, _), (_, after, _) in zip(trace, trace[1:])]
    return sum(1 for a, b in zip(speeds, speeds[1:]) if a > 0.1 >= b)


def test_glosa_crosses_without_stopping_where_the_ego_stops_without_it():
    plan = lambda t: fixed_time(t, 10.0, 3.0, 20.0, 4.0)  # noqa: E731 -- red from 17 to 37 s: we arrive in it
    with_glosa, without = drive(planner(True), plan), drive(planner(False), plan)
    assert (stops(with_glosa), stops(without)) == (0, 1)
    assert entered_on(with_glosa) == entered_on(without) == GREEN
