"""A signalised intersection's roadside unit in the simulator: its MAPEMs and SPATEMs are real GN packets that the
stack's V2X decoder reads into the lanes, signal groups and phase end times of the intersection, and they decode to
the same protobuf as the same intersection written by hand and encoded by asn1tools straight from TS 103 301's
modules; signed with the run's PKI, a stack of the run verifies them."""

import datetime as dt

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.fault_config import MapLaneOffset, SpatLoss, SpatTimeJump
from coopdrive.services.sim.intent_encoder import IntentEncoder
from coopdrive.services.sim.intersection_config import SignalApproach, SignalisedIntersection
from coopdrive.services.sim.participants import IntentKind
from coopdrive.services.sim.sender_signing import SenderSigning
from coopdrive.services.sim.signal_plan import SignalPlan, SignalStage
from coopdrive.services.sim.signal_rsu import SignalBroadcaster
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import ItsClock, tai_ms_from_utc
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v1 import sim_pb2
from tests.v2x import infrastructure_messages as messages

EPOCH = dt.datetime(2016, 5, 28, 10, 0, tzinfo=dt.timezone.utc)
RSU_STATION = 4900
# The intersection map's main road: eastbound lane 0 from x = -300 m at y = -1.75 m, westbound from x = 300 m at
# y = 1.75 m; station 290 m is 10 m before the reference point either way.
INTERSECTION = SignalisedIntersection(
    intersection_id=12, name="corridor west", x_m=0.0, y_m=0.0,
    plan=SignalPlan(stages=[SignalStage(groups=[1, 2], green_s=20.0), SignalStage(groups=[3], green_s=10.0)]),
    approaches=[SignalApproach(road="main_eastbound", lane=0, stop_station_m=290.0, box_length_m=20.0, signal_group=1,
                               ingress_lane_id=1, egress_lane_id=2),
                SignalApproach(road="main_westbound", lane=0, stop_station_m=290.0, box_length_m=20.0, signal_group=2,
                               ingress_lane_id=3, egress_lane_id=4)])
# 2016-05-28 10:00 UTC: day 148 of a leap year, 10 h in.
MINUTE_OF_YEAR = 148 * 1440 + 600


@pytest.fixture(scope="module")
def road_map():
    return RoadMap.load("intersection")


@pytest.fixture
def broadcaster(road_map):
    return SignalBroadcaster(INTERSECTION, RSU_STATION, road_map.lanes_of_road, road_map.to_geodetic, EPOCH)


def sent(broadcaster, road_map, now_s):
    """{kind: packet} of what the unit sends at now_s."""
    encoder = IntentEncoder(road_map.to_geodetic, EPOCH)
    return {intent.kind: (intent, encoder.encode(intent))
            for intent in broadcaster.messages_due(now_s, "rsu_west", 15.0, 15.0)}


def xy(x_cm, y_cm):
    """The smallest Node-XY alternative for the offset, as another encoder would choose it."""
    limits = {"node-XY1": 511, "node-XY2": 1023, "node-XY3": 2047, "node-XY4": 4095, "node-XY5": 8191}
    name = next((n for n, limit in limits.items() if max(abs(x_cm), abs(y_cm)) <= limit), "node-XY6")
    return {"delta": (name, {"x": x_cm, "y": y_cm})}


def lane(lane_id, direction, nodes, connects_to=None, approach=None):
    value = {"laneID": lane_id, "laneAttributes": {"directionalUse": (direction, 2), "sharedWith": messages.NO_SHARING,
                                                   "laneType": messages.VEHICLE_LANE},
             "nodeList": ("nodes", nodes)}
    if connects_to is not None:
        value["connectsTo"] = [{"connectingLane": {"lane": connects_to[0]}, "signalGroup": connects_to[1]}]
        value["ingressApproach"] = approach
    return value


def hand_written_mapem(road_map):
    """Eastbound: ingress lane 1 from its stop line 10 m west of the centre back 250 m in 50 m steps, egress lane 2
    from 10 m east on for 50 m; westbound the mirror image (lanes 3 and 4)."""
    latitude_deg, longitude_deg, _ = road_map.to_geodetic(0.0, 0.0)
    lanes = [lane(1, b"\x80", [xy(-1000, -175)] + [xy(-5000, 0)] * 5, (2, 1), 1),
             lane(2, b"\x40", [xy(1000, -175), xy(5000, 0)]),
             lane(3, b"\x80", [xy(1000, 175)] + [xy(5000, 0)] * 5, (4, 2), 2),
             lane(4, b"\x40", [xy(-1000, 175), xy(-5000, 0)])]
    intersection = {"id": {"id": 12}, "revision": 1, "name": "corridor west",
                    "refPoint": {"lat": round(latitude_deg * 1e7), "long": round(longitude_deg * 1e7)},
                    "laneWidth": 350, "laneSet": lanes}
    return {"header": {"protocolVersion": 2, "messageId": 5, "stationId": RSU_STATION},
            "map": {"msgIssueRevision": 1, "intersections": [intersection]}}


def events(*phases):
    return [{"eventState": state, "timing": {"minEndTime": end, "maxEndTime": end, "likelyTime": end}}
            for state, end in phases]


def hand_written_spatem():
    """5 s into the cycle (10:00:05 UTC): groups 1 and 2 green until 10:00:20, amber to :23, red to :39, red-amber to
    :40; group 3 red until :24, red-amber to :25, green to :35, amber to :38 (TimeMarks in tenths of the hour)."""
    main = events(("protected-Movement-Allowed", 200), ("protected-clearance", 230), ("stop-And-Remain", 390),
                  ("pre-Movement", 400))
    side = events(("stop-And-Remain", 240), ("pre-Movement", 250), ("protected-Movement-Allowed", 350),
                  ("protected-clearance", 380))
    intersection = {"id": {"id": 12}, "revision": 1, "name": "corridor west", "status": (b"\x04\x00", 16),
                    "moy": MINUTE_OF_YEAR, "timeStamp": 5000,
                    "states": [{"signalGroup": 1, "state-time-speed": main},
                               {"signalGroup": 2, "state-time-speed": main},
                               {"signalGroup": 3, "state-time-speed": side}]}
    return {"header": {"protocolVersion": 2, "messageId": 4, "stationId": RSU_STATION},
            "spat": {"timeStamp": MINUTE_OF_YEAR, "intersections": [intersection]}}


def theirs(kind, value):
    return decode_packet(messages.gn_packet(BtpPort[kind], messages.encoded(kind, value))).content


def test_the_units_mapem_decodes_to_ingress_lanes_starting_at_their_stop_lines_with_their_signal_groups(
        broadcaster, road_map):
    _, packet = sent(broadcaster, road_map, 0.0)[IntentKind.MAPEM]
    decoded = decode_packet(packet)
    assert (decoded.message_type, decoded.btp.destination_port, decoded.station_id) == \
        (InfrastructureMessage.MAPEM, 2003, RSU_STATION)
    (intersection,) = decoded.content.intersections
    assert (intersection.id.id, list(intersection.signal_groups)) == (12, [1, 2])
    ingress = intersection.lanes[0]
    assert (ingress.lane_id, ingress.ingress_path, ingress.egress_path, ingress.lane_type) == \
        (1, True, False, pb.LANE_TYPE_VEHICLE)
    # The first node is the stop line, 10 m west of the reference point in the eastbound lane.
    assert (ingress.nodes[0].east_m, ingress.nodes[0].north_m) == (pytest.approx(-10.0), pytest.approx(-1.75))
    assert sum(node.east_m for node in ingress.nodes) == pytest.approx(-260.0)
    assert [(c.to_lane_id, c.signal_group) for c in ingress.connections] == [(2, 1)]


def test_the_units_mapem_decodes_to_the_same_protobuf_as_the_intersection_written_by_another_encoder(
        broadcaster, road_map):
    _, packet = sent(broadcaster, road_map, 0.0)[IntentKind.MAPEM]
    assert decode_packet(packet).content == theirs("MAPEM", hand_written_mapem(road_map))


def test_the_units_spatem_states_each_groups_phases_and_end_times_as_another_encoder_writes_them(broadcaster,
                                                                                                  road_map):
    broadcaster.step(5.0, [])
    _, packet = sent(broadcaster, road_map, 5.0)[IntentKind.SPATEM]
    decoded = decode_packet(packet)
    assert (decoded.message_type, decoded.btp.destination_port) == (InfrastructureMessage.SPATEM, 2004)
    assert decoded.content == theirs("SPATEM", hand_written_spatem())
    green = decoded.content.intersections[0].signal_groups[0].events[0]
    assert (green.state, green.min_end_time_s) == (pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED,
                                                   pytest.approx(20.0))


def test_phase_ends_past_the_hour_wrap_to_its_start_as_timemarks_do(broadcaster):
    # 10:59:58 UTC, 38 s into the 40 s cycle: group 1 red until 10:59:59, red-amber until 11:00:00, green to 11:00:20.
    red, red_amber, green, _ = broadcaster.spatem(3598.0).intersections[0].signal_groups[0].events
    assert [event.min_end_time_s for event in (red, red_amber, green)] == \
        [pytest.approx(3599.0), pytest.approx(0.0), pytest.approx(20.0)]


def test_the_unit_sends_its_mapem_once_a_second_and_its_spatem_ten_times(broadcaster):
    kinds = [intent.kind for tenth in range(20) for intent in broadcaster.messages_due(tenth * 0.1, "rsu", 0.0, 0.0)]
    assert (kinds.count(IntentKind.MAPEM), kinds.count(IntentKind.SPATEM)) == (2, 20)


def test_a_roadside_units_signed_spatem_of_the_run_verifies_at_the_scenario_clock(broadcaster, road_map, tmp_path):
    pki = create_test_pki(tmp_path, ["rsu_west"], valid_from_tai_s=tai_ms_from_utc(EPOCH) // 1000 - 3600,
                          roadside_units=["rsu_west"])
    intent, packet = sent(broadcaster, road_map, 2.0)[IntentKind.SPATEM]
    signed = SenderSigning(tmp_path, EPOCH).seal(intent, packet)
    opened = SecurityVerifier(pki.store()).open(signed, ItsClock(EPOCH.timestamp()).tai_ms(2.05) * 1000)
    assert opened.result.ok and opened.verified
    assert decode_packet(signed).content == decode_packet(packet).content


def test_a_vehicles_ticket_may_not_sign_a_spatem(broadcaster, road_map, tmp_path):
    pki = create_test_pki(tmp_path, ["rsu_west"], valid_from_tai_s=tai_ms_from_utc(EPOCH) // 1000 - 3600)
    intent, packet = sent(broadcaster, road_map, 2.0)[IntentKind.SPATEM]
    signed = SenderSigning(tmp_path, EPOCH).seal(intent, packet)
    opened = SecurityVerifier(pki.store()).open(signed, ItsClock(EPOCH.timestamp()).tai_ms(2.05) * 1000)
    assert opened.result.reason is RejectReason.PSID_NOT_PERMITTED


def test_a_vehicle_on_an_actuated_approachs_detector_holds_its_green_and_the_spatem_says_so(road_map):
    actuated = INTERSECTION.model_copy(update={"plan": SignalPlan(stages=[
        SignalStage(groups=[1, 2], green_s=20.0, max_extension_s=6.0), SignalStage(groups=[3], green_s=10.0)])})
    unit = SignalBroadcaster(actuated, RSU_STATION, road_map.lanes_of_road, road_map.to_geodetic, EPOCH)
    # Rear axle 30 m before the eastbound stop line (x = -10 m), driving east.
    waiting = sim_pb2.VehicleTruth(vehicle_id="car", x_m=-40.0, y_m=-1.75, heading_rad=0.0, length_m=4.5,
                                   width_m=1.8)
    for tenth in range(1, 231):
        unit.step(tenth * 0.1, [waiting])
    spatem = unit.spatem(23.0)
    assert spatem.intersections[0].status.traffic_dependent_operation
    green = spatem.intersections[0].signal_groups[0].events[0]
    assert green.state == pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED
    # Held 3 s past its 20 s so far, it may last 3 s more.
    assert green.max_end_time_s == pytest.approx(26.0, abs=0.2)


def test_a_spat_loss_silences_the_spatem_and_leaves_the_mapem(broadcaster):
    broadcaster.set_faults([SpatLoss(type="spat_loss", unit_id="rsu_west", start_s=0.0)])
    kinds = {intent.kind for intent in broadcaster.messages_due(0.0, "rsu_west", 0.0, 0.0)}
    assert kinds == {IntentKind.MAPEM}
    broadcaster.set_faults([])
    assert IntentKind.SPATEM in {intent.kind for intent in broadcaster.messages_due(0.1, "rsu_west", 0.0, 0.0)}


def test_a_spat_time_jump_moves_every_stated_end_and_not_the_lights(broadcaster):
    broadcaster.set_faults([SpatTimeJump(type="spat_time_jump", unit_id="rsu_west", start_s=0.0, jump_s=10.0)])
    green = broadcaster.spatem(5.0).intersections[0].signal_groups[0].events[0]
    assert (green.min_end_time_s, green.likely_time_s) == (pytest.approx(30.0), pytest.approx(30.0))
    assert broadcaster.controller.phases(1, 5.0)[0].min_end_s == pytest.approx(20.0)


def test_a_map_lane_offset_moves_the_reference_point_and_every_lane_with_it(broadcaster, road_map):
    broadcaster.set_faults([MapLaneOffset(type="map_lane_offset", unit_id="rsu_west", start_s=0.0, north_m=3.5)])
    moved, = broadcaster.mapem.intersections
    latitude_deg, longitude_deg, _ = road_map.to_geodetic(0.0, 3.5)
    assert (moved.reference_latitude_deg, moved.reference_longitude_deg) == \
        (pytest.approx(latitude_deg, abs=1e-9), pytest.approx(longitude_deg, abs=1e-9))
    assert (moved.lanes[0].nodes[0].east_m, moved.lanes[0].nodes[0].north_m) == \
        (pytest.approx(-10.0), pytest.approx(-1.75))
