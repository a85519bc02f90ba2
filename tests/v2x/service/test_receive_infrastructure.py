"""The v2x service's receive path with roadside units' messages: a real SPATEM and hand-written MAPEM, SREM and
SSEM are published on their bus topics and counted for the roadside unit's station; thousands of mutated ones
(the full run, `python -m tests.v2x.service.infrastructure_fuzz`, takes 100 000) never raise and each is accepted
or counted under a reason."""

import pytest

from coopdrive.v2x.reasons import RejectReason
from coopdrive.v1 import infrastructure_pb2 as pb
from tests.v2x import infrastructure_messages as messages
from tests.v2x.infrastructure_messages import RSU_STATION

from .infrastructure_fuzz import run, seeds, started_service

PACKETS = 3000
SLOWEST_PACKET_CPU_S = 0.1
REAL_SPATEM_STATION = 10430022
TOPICS = ("v2x/spatem", "v2x/mapem", "v2x/srem", "v2x/ssem")


@pytest.fixture
def service(tmp_path):
    service, ctx, radio = started_service(tmp_path)
    yield service, ctx
    service.stop()
    radio.close()


def test_a_real_spatem_and_our_mapem_srem_and_ssem_are_published_on_their_topics_and_the_rsus_are_listed(service):
    service, ctx = service
    for packet in seeds():
        service.on_datagram(packet)
    service.flush_received(ctx.now_s())
    service.publish_status(ctx.now_s())
    spatems = ctx.messages("v2x/spatem")
    assert [content.station_id for content in spatems] == [REAL_SPATEM_STATION, RSU_STATION, RSU_STATION]
    assert spatems[0].intersections[0].signal_groups[0].events[0].state == pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN
    (mapem, _) = ctx.messages("v2x/mapem")
    assert [lane.lane_id for lane in mapem.intersections[0].lanes] == [1, 2]
    assert [len(ctx.messages(topic)) for topic in TOPICS] == [3, 2, 2, 2]
    assert (service.counters["received_spatem"], service.counters["received_mapem"]) == (3, 2)
    stations = {station.station_id: station for station in ctx.messages("v2x/status")[-1].stations}
    assert stations[RSU_STATION].messages_received == 8 and stations[REAL_SPATEM_STATION].messages_received == 1


def test_a_mapem_whose_lane_list_is_cut_short_is_counted_as_malformed_and_nothing_is_published(service):
    service, ctx = service
    packet = messages.gn_packet(messages.BtpPort.MAPEM, messages.encoded("MAPEM", messages.mapem())[:-12])
    service.on_datagram(packet)
    service.flush_received(ctx.now_s())
    assert service.reception.rejected_by_reason == {RejectReason.MALFORMED_ASN1.value: 1}
    assert ctx.messages("v2x/mapem") == []


def test_3000_mutated_infrastructure_messages_pass_the_receive_path_each_accepted_or_counted_under_a_reason(
        tmp_path):
    outcome, counters = run(PACKETS, tmp_path)
    assert outcome.packets == PACKETS
    assert outcome.accepted + outcome.own + outcome.beacons + sum(outcome.rejected.values()) == PACKETS
    assert set(outcome.rejected) <= {reason.value for reason in RejectReason}
    assert outcome.slowest_packet_cpu_s < SLOWEST_PACKET_CPU_S
    for reason in ("malformed_asn1", "message_id_port_mismatch", "unsupported_protocol_version"):
        assert outcome.rejected[reason] > 0, (reason, outcome.rejected)
    for kind in ("spatem", "mapem", "srem", "ssem"):
        assert counters[f"received_{kind}"] > 0, (kind, counters)
