"""SPATEM, MAPEM, SREM and SSEM decoded into protobuf: a real roadside unit's signed SPATEM, and messages of both
protocol versions written by hand and encoded by asn1tools straight from TS 103 301's modules."""

import pytest

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.mapping.mapem import mapem_from_asn
from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v1 import infrastructure_pb2 as pb
from tests.shared_data import shared_file
from tests.v2x import infrastructure_messages as messages

SPATEM_STATION = 10430022
PROTOCOL_VERSIONS = (1, 2)


def real_spatem():
    packets = [packet.gn_packet for packet in read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))]
    return decode_packet(packets[3])


def test_the_real_signed_spatem_decodes_to_its_intersection_and_25_signal_groups_with_their_phases_and_end_times():
    decoded = real_spatem()
    assert decoded.message_type is InfrastructureMessage.SPATEM and decoded.security.verified
    content = decoded.content
    assert (content.station_id, content.protocol_version, content.minute_of_year) == (SPATEM_STATION, 2, 470007)
    (intersection,) = content.intersections
    assert (intersection.id.region, intersection.id.id, intersection.revision) == (30, 63, 2)
    assert (intersection.minute_of_year, intersection.second_of_minute_s) == (470007, pytest.approx(4.456))
    assert intersection.status == pb.IntersectionStatus(traffic_dependent_operation=True)
    assert [group.signal_group for group in intersection.signal_groups] == list(range(1, 26))
    first = intersection.signal_groups[0]
    assert [event.state for event in first.events] == [
        pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN, pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT,
        pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED, pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE,
        pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN]
    # TimeMark 16360 (tenths of a second of the hour): red until 1636.0 s, i.e. 27 min 16 s after the hour.
    assert (first.events[0].min_end_time_s, first.events[0].likely_time_s, first.events[0].max_end_time_s,
            first.events[0].confidence) == (pytest.approx(1636.0), pytest.approx(1636.0), pytest.approx(1636.0), 14)
    last = first.events[4]
    assert (last.min_end_time_s, last.likely_time_s, last.max_end_time_s, last.confidence) == \
        (pytest.approx(1731.0), pytest.approx(1731.0), pytest.approx(1758.0), 3)
    permissive = intersection.signal_groups[3].events[2]
    assert (permissive.state, permissive.min_end_time_s, permissive.max_end_time_s) == \
        (pb.MOVEMENT_PHASE_STATE_PERMISSIVE_MOVEMENT_ALLOWED, pytest.approx(1717.0), pytest.approx(1752.0))


def decode(kind: str, value: dict):
    return decode_packet(messages.gn_packet(BtpPort[kind], messages.encoded(kind, value)))


@pytest.mark.parametrize("version", PROTOCOL_VERSIONS)
def test_a_mapem_written_by_another_encoder_gives_its_lanes_nodes_in_metres_connections_and_signal_groups(version):
    decoded = decode("MAPEM", messages.mapem(version))
    content = decoded.content
    assert (decoded.message_type, content.protocol_version, content.station_id, content.message_revision,
            content.minute_of_year) == (InfrastructureMessage.MAPEM, version, messages.RSU_STATION, 3, 100000)
    (intersection,) = content.intersections
    assert (intersection.id.region, intersection.id.id, intersection.revision, intersection.name) == \
        (7, 1234, 5, "Lindholmen")
    assert (intersection.reference_latitude_deg, intersection.reference_longitude_deg,
            intersection.reference_elevation_m, intersection.lane_width_m) == \
        (pytest.approx(57.7081234), pytest.approx(11.9393456), pytest.approx(12.3), pytest.approx(3.5))
    assert list(intersection.signal_groups) == [2, 4]
    lane, crosswalk = intersection.lanes
    assert (lane.lane_id, lane.ingress_approach, lane.ingress_path, lane.egress_path, lane.lane_type) == \
        (1, 1, True, False, pb.LANE_TYPE_VEHICLE)
    assert [(node.east_m, node.north_m) for node in lane.nodes[:2]] == \
        [(pytest.approx(-1.5), pytest.approx(0.2)), (0.0, pytest.approx(-30.0))]
    assert (lane.nodes[2].latitude_deg, lane.nodes[2].longitude_deg) == (pytest.approx(57.708), pytest.approx(11.939))
    assert not lane.nodes[2].HasField("east_m")
    assert [(c.to_lane_id, c.signal_group, c.connection_id) for c in lane.connections[:1]] == [(5, 4, 9)]
    remote = lane.connections[1]
    assert (remote.to_lane_id, remote.signal_group, remote.remote_intersection.id, remote.HasField("connection_id")) \
        == (6, 2, 99, False)
    assert (crosswalk.lane_type, crosswalk.name, crosswalk.egress_approach, crosswalk.ingress_path,
            crosswalk.egress_path, len(crosswalk.nodes)) == (pb.LANE_TYPE_CROSSWALK, "north crossing", 2, True, True, 0)
    assert crosswalk.computed == pb.ComputedLane(reference_lane_id=1, offset_east_m=3.5, offset_north_m=-40.0)


@pytest.mark.parametrize("version", PROTOCOL_VERSIONS)
def test_a_spatem_with_regional_extensions_gives_each_signal_group_its_phases_and_an_unknown_end_stays_absent(
        version):
    content = decode("SPATEM", messages.spatem(version)).content
    assert (content.protocol_version, content.minute_of_year) == (version, 200000)
    (intersection,) = content.intersections
    assert (intersection.id.id, intersection.id.HasField("region"), intersection.revision) == (1234, False, 6)
    assert intersection.status == pb.IntersectionStatus(fixed_time_operation=True)
    assert intersection.second_of_minute_s == pytest.approx(30.5)
    green, red = intersection.signal_groups
    assert (green.signal_group, red.signal_group, red.movement_name) == (4, 2, "left turn")
    assert green.events[0] == pb.MovementEvent(state=pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED,
                                               min_end_time_s=120.0, max_end_time_s=135.0, likely_time_s=127.5,
                                               confidence=10)
    # minEndTime 36001 is "unknown": the clearance's end is absent, not 3600.1 s.
    assert green.events[1] == pb.MovementEvent(state=pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE)
    assert red.events[0] == pb.MovementEvent(state=pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN)


@pytest.mark.parametrize("version", PROTOCOL_VERSIONS)
def test_an_srem_names_the_requesting_station_its_role_the_intersection_and_the_lanes(version):
    content = decode("SREM", messages.srem(version)).content
    assert (content.station_id, content.minute_of_year, content.second_of_minute_s, content.sequence_number) == \
        (messages.RSU_STATION, 200000, pytest.approx(30.5), 8)
    assert content.requestor == pb.Requestor(station_id=4242, role=1)
    (request,) = content.requests
    assert request == pb.SignalRequest(intersection=pb.IntersectionReference(id=1234), request_id=17,
                                       request_type=pb.PRIORITY_REQUEST_TYPE_REQUEST,
                                       inbound=pb.AccessPoint(lane_id=1), outbound=pb.AccessPoint(approach_id=3))


@pytest.mark.parametrize("version", PROTOCOL_VERSIONS)
def test_an_ssem_gives_each_intersection_its_answer_to_the_request(version):
    content = decode("SSEM", messages.ssem(version)).content
    assert (content.HasField("minute_of_year"), content.second_of_minute_s) == (False, pytest.approx(31.0))
    (intersection,) = content.intersections
    assert (intersection.intersection.id, intersection.sequence_number) == (1234, 2)
    assert list(intersection.entries) == [pb.SignalStatusEntry(
        requester=pb.Requestor(station_id=4242, role=1), request_id=17, inbound=pb.AccessPoint(lane_id=1),
        status=pb.PRIORITIZATION_RESPONSE_GRANTED)]


def test_an_infrastructure_message_under_a_protocol_version_we_do_not_know_is_refused_by_that_reason():
    with pytest.raises(V2xDecodeError) as refused:
        decode("SPATEM", messages.spatem(3))
    assert refused.value.reason is RejectReason.UNSUPPORTED_PROTOCOL_VERSION


def test_a_mapem_on_the_spatem_port_is_refused_as_a_message_id_port_mismatch():
    packet = messages.gn_packet(BtpPort.SPATEM, messages.encoded("MAPEM", messages.mapem()))
    with pytest.raises(V2xDecodeError) as refused:
        decode_packet(packet)
    assert refused.value.reason is RejectReason.MESSAGE_ID_PORT_MISMATCH


def test_an_ssem_and_an_iclcm_share_message_id_10_and_each_port_reads_its_own():
    decoded = decode("SSEM", messages.ssem())
    assert decoded.message_type is InfrastructureMessage.SSEM and isinstance(decoded.content, pb.SsemContent)


def test_a_lane_type_or_node_added_after_our_module_maps_to_unknown_and_an_empty_node():
    """asn1tools reads a CHOICE alternative it does not know as (None, None): the lane is kept."""
    value = messages.mapem()
    lane = value["map"]["intersections"][0]["laneSet"][0]
    lane["laneAttributes"] = {**lane["laneAttributes"], "laneType": (None, None)}
    lane["nodeList"] = ("nodes", [{"delta": (None, None)}, *lane["nodeList"][1][1:]])
    (first, _) = mapem_from_asn(value).intersections[0].lanes
    assert first.lane_type == pb.LANE_TYPE_UNKNOWN and first.nodes[0] == pb.LaneNode()
