"""A platoon split by a traffic light: the member that stops at the line lets go the partner already across it
(control then follows the line, not a car driving on) and its iCLCM names no forward partner, heading the part
behind the line; a partner still short of the line stays followed."""

from __future__ import annotations

import pytest
from planner_world import RSU, inputs, obj, rsu_start, scene
from planner_world import iclcm as iclcm_from
from signal_world import AMBER, RED, ego_at, heard, light, mapem

from coopdrive.services.planner.config import PlannerLogicConfig
from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import planner_pb2

PARTNER, PARTNER_OBJECT = 7, 1
# The rear axle 80 m before the signal_world's stop line: the front bumper 66.2 m from it, beyond the comfortable
# stopping distance on amber (39 m at 13.9 m/s).
EGO_X_M = -80.0
TO_LINE_M = 66.2
AMBER_NOW = light((AMBER, 3.0), (RED, 30.0))


def step(scenario: int, partner_gap_m: float, **extra) -> tuple[Planner, planner_pb2.BehaviourRequest]:
    p = Planner(PlannerLogicConfig(cruise_speed_mps=13.9))
    partner = scene(obj(PARTNER_OBJECT, PARTNER, gap_m=partner_gap_m, speed_mps=13.9), forward_mio=PARTNER_OBJECT)
    request, _ = p.step(0.0, inputs(scenario, ego=ego_at(EGO_X_M), scene=partner, mapems=heard(mapem(), 0.0),
                                    spatems=heard(AMBER_NOW, 0.0), **extra))
    return p, request


def predecessors(request: planner_pb2.BehaviourRequest) -> list[int]:
    return [t.object_id for t in request.targets if t.role == planner_pb2.TARGET_ROLE_PREDECESSOR]


def test_stopping_on_amber_it_lets_go_the_car_ahead_already_across_the_line():
    p, request = step(planner_pb2.SCENARIO_FOLLOW, partner_gap_m=TO_LINE_M + 4.0)
    assert p.lights_machine.state.name == "STOP"
    assert request.has_stop_line and request.stop_line_distance_m == pytest.approx(TO_LINE_M, abs=0.05)
    assert predecessors(request) == []


def test_the_car_ahead_still_short_of_the_line_stays_followed_while_it_stops():
    p, request = step(planner_pb2.SCENARIO_FOLLOW, partner_gap_m=TO_LINE_M - 20.0)
    assert p.lights_machine.state.name == "STOP" and request.has_stop_line
    assert predecessors(request) == [PARTNER_OBJECT]


def test_a_platoon_member_stopping_at_the_line_names_no_forward_partner_in_its_iclcm():
    platoon = {"platoon_id": 2, "iclcms": {PARTNER: iclcm_from(PARTNER, 0.0), RSU: rsu_start(0.0)}}
    p, request = step(planner_pb2.SCENARIO_PLATOON, partner_gap_m=TO_LINE_M + 4.0, **platoon)
    assert p.state_name == "JOINING" and p.lights_machine.state.name == "STOP"
    assert request.HasField("iclcm") and request.iclcm.forward_id == 0
    assert predecessors(request) == []
    _, short_of_it = step(planner_pb2.SCENARIO_PLATOON, partner_gap_m=TO_LINE_M - 20.0, **platoon)
    assert short_of_it.iclcm.forward_id == PARTNER
