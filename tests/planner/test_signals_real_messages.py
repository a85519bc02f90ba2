"""The traffic lights on messages our code did not write: a MAPEM and SPATEMs encoded by asn1tools compiled straight
from TS 103 301's modules (shared/asn1/dsrc) and decoded by our v2x path give the planner the decisions their
protobuf equivalent gives; the real roadside unit's signed SPATEM (shared/data/v2x) drives its advice."""

from __future__ import annotations

import pytest
from planner_world import inputs
from signal_world import AMBER, GREEN, LEFT, RED, RIGHT, STRAIGHT, ego_at, heard, light, mapem

from coopdrive.recording.capture import read_gn_packets
from coopdrive.services.planner.config import PlannerLogicConfig, SignalConfig
from coopdrive.services.planner.planner import Planner
from coopdrive.services.planner.signals.advice import Advice, Approach, advise
from coopdrive.services.planner.signals.spat_tracker import SpatTracker
from coopdrive.services.planner.signals.time_mark import unix_s_of_minute_of_year
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.timebase import ItsClock
from coopdrive.v1 import planner_pb2
from tests.shared_data import shared_file
from tests.v2x import infrastructure_messages as messages

LIMIT_MPS = 13.9
STATE_NAME = {GREEN: "protected-Movement-Allowed", AMBER: "protected-clearance", RED: "stop-And-Remain"}
# NodeOffsetPointXY alternatives, the smallest first, and the largest offset (cm) each holds.
NODE_SIZES = (("node-XY1", 511), ("node-XY2", 1023), ("node-XY3", 2047), ("node-XY4", 4095), ("node-XY5", 8191),
              ("node-XY6", 32767))
UNKNOWN_TIME_MARK = 36001


def asn_lane(lane_id: int, offsets_m: list[tuple[float, float]], ingress: bool, connections=()) -> dict:
    nodes = []
    for east_m, north_m in offsets_m:
        x, y = round(east_m * 100), round(north_m * 100)
        kind = next(name for name, largest in NODE_SIZES if max(abs(x), abs(y)) <= largest)
        nodes.append({"delta": (kind, {"x": x, "y": y})})
    lane = {"laneID": lane_id, "laneAttributes": {"directionalUse": (b"\x80" if ingress else b"\x40", 2),
                                                  "sharedWith": messages.NO_SHARING,
                                                  "laneType": messages.VEHICLE_LANE},
            "nodeList": ("nodes", nodes)}
    if connections:
        lane["connectsTo"] = [{"connectingLane": {"lane": to}, "signalGroup": group} for to, group in connections]
    return lane


def asn_mapem() -> dict:
    """signal_world's intersection, written as TS 103 301's MAPEM."""
    lanes = [asn_lane(1, [(-10.0, -1.75), (-100.0, 0.0), (-200.0, 0.0)], True,
                      [(2, STRAIGHT), (3, LEFT), (4, RIGHT)]),
             asn_lane(2, [(10.0, -1.75), (100.0, 0.0)], False), asn_lane(3, [(1.75, 10.0), (0.0, 100.0)], False),
             asn_lane(4, [(-1.75, -10.0), (0.0, -100.0)], False)]
    intersection = {"id": {"id": 12}, "revision": 1, "refPoint": {"lat": 500_000_000, "long": 50_000_000},
                    "laneWidth": 350, "laneSet": lanes}
    return {"header": messages.header(2, 5), "map": {"msgIssueRevision": 1, "intersections": [intersection]}}


def asn_spatem(phases) -> dict:
    """Group 1 through (state, likely end in seconds of the hour), minEndTime unknown, as signal_world.light."""
    events = [{"eventState": STATE_NAME[state],
               "timing": {"minEndTime": UNKNOWN_TIME_MARK, "likelyTime": round(end_s * 10)}} for state, end_s in phases]
    intersection = {"id": {"id": 12}, "revision": 1, "status": (b"\x00\x00", 16),
                    "states": [{"signalGroup": 1, "state-time-speed": events}]}
    return {"header": messages.header(2, 4), "spat": {"intersections": [intersection]}}


def decoded(kind: str, value: dict):
    return decode_packet(messages.gn_packet(BtpPort[kind], messages.encoded(kind, value))).content


def decision(map_content, spat_content, x_m: float, speed_mps: float = LIMIT_MPS, glosa: bool = True):
    p = Planner(PlannerLogicConfig(cruise_speed_mps=LIMIT_MPS), glosa=glosa)
    request, _ = p.step(0.0, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(x_m, speed_mps),
                                    mapems=heard(map_content, 0.0), spatems=heard(spat_content, 0.0)))
    return (p.lights_machine.state.name, request.has_stop_line, round(request.stop_line_distance_m, 2),
            round(request.desired_speed_mps, 3))


SITUATIONS = [
    (-180.0, ((RED, 60.0), (GREEN, 90.0))),
    (-180.0, ((RED, 15.0), (GREEN, 45.0))),
    (-180.0, ((GREEN, 60.0),)),
    (-180.0, ((GREEN, 5.0), (AMBER, 8.0), (RED, 20.0), (GREEN, 50.0))),
    (-30.0, ((AMBER, 3.0), (RED, 30.0))),
    (-80.0, ((AMBER, 3.0), (RED, 30.0))),
]


@pytest.mark.parametrize("glosa", [True, False])
@pytest.mark.parametrize("x_m, phases", SITUATIONS)
def test_a_mapem_and_spatem_written_by_another_encoder_give_the_decisions_of_their_protobuf_equivalent(
        x_m, phases, glosa):
    theirs = decision(decoded("MAPEM", asn_mapem()), decoded("SPATEM", asn_spatem(phases)), x_m, glosa=glosa)
    ours = decision(mapem(), light(*phases), x_m, glosa=glosa)
    assert theirs == ours
    assert theirs[0] != "IDLE"


def real_spatem():
    packets = [packet.gn_packet for packet in read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))]
    return decode_packet(packets[3]).content


def real_spat_time_unix_s(content) -> float:
    """The SPATEM's own time stamp (minute 470007 of the year, 4.456 s): 27 min 4.456 s after an hour began."""
    (intersection,) = content.intersections
    return unix_s_of_minute_of_year(2023, intersection.minute_of_year, intersection.second_of_minute_s)


@pytest.mark.parametrize("to_line_m, glosa, advice, speed_mps", [
    # Red until 1636.0 s of the hour, red-amber until 1638.0, green until 1666.0: 13.544 s from the stamp, +1 s.
    (150.0, True, Advice.GLOSA, 150.0 / 14.544),
    (150.0, False, Advice.STOP, LIMIT_MPS),
    # Green too far off for 20 km/h: stop.
    (30.0, True, Advice.STOP, LIMIT_MPS),
])
def test_the_real_rsus_spatem_drives_the_advice_for_its_first_signal_group(to_line_m, glosa, advice, speed_mps):
    content = real_spatem()
    now_s = real_spat_time_unix_s(content)
    tracker = SpatTracker(ItsClock(), SignalConfig().timing_tolerance_s)
    tracker.on_spatem(content, now_s)
    timing = tracker.latest[(30, 63, 1)]
    assert timing.current.end_s - now_s == pytest.approx(11.544)
    advised = advise(timing, Approach(now_s, to_line_m, LIMIT_MPS, LIMIT_MPS), SignalConfig(), glosa)
    assert (advised.advice, advised.speed_mps) == (advice, pytest.approx(speed_mps, rel=1e-3))


def test_the_real_rsus_spatem_reaches_the_planner_on_a_lane_of_its_intersection():
    content = real_spatem()
    now_s = real_spat_time_unix_s(content)
    p = Planner(PlannerLogicConfig(cruise_speed_mps=LIMIT_MPS))
    request, _ = p.step(now_s, inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(-163.8),
                                      mapems=heard(mapem(intersection_id=63, region=30), now_s),
                                      spatems=heard(content, now_s)))
    assert p.lights.view.status.name == "OK" and p.lights_machine.state.name == "GLOSA"
    assert request.desired_speed_mps == pytest.approx(150.0 / 14.544, rel=1e-3) and request.has_stop_line
