"""Stacks in one process share each packet's UPER decode (recent_decodes.py): it must be the decode the bytes give,
and nothing that reads it may change it."""

import copy

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v2x.its_pdu import PDU_TYPE_NAMES, ItsCodec, ItsMessageId, peek_its_header
from coopdrive.v2x.mapping.cam import cam_from_asn, cam_to_asn
from coopdrive.v2x.mapping.denm import denm_from_asn, denm_to_asn
from coopdrive.v2x.mapping.iclcm import iclcm_from_asn, iclcm_to_asn
from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.reasons import V2xDecodeError, V2xEncodeError
from coopdrive.v2x.recent_decodes import RecentDecodes
from coopdrive.v1 import its_pb2
from tests.shared_data import shared_file
from tests.v2x.any_content import any_message

REAL_CAPTURES = ("v2x/considerit_signed_testvectors.pcap", "v2x/flexstack_cam_vam_beacons.pcap",
                 "v2x/msvan3t_cam_cpm_trace.pcapng")
MAPPINGS = {
    "CAM": (ItsMessageId.CAM, its_pb2.CamContent, cam_to_asn, cam_from_asn, (1, 2)),
    "DENM": (ItsMessageId.DENM, its_pb2.DenmContent, denm_to_asn, denm_from_asn, (1, 2)),
    "iCLCM": (ItsMessageId.ICLCM, its_pb2.IclcmContent, iclcm_to_asn, iclcm_from_asn, (1,)),
}
CODEC = ItsCodec()


def fresh_decode(uper: bytes) -> dict:
    """asn1tools' own decode, past the memo."""
    header = peek_its_header(uper)
    return CODEC.spec(header.protocol_version).decode(PDU_TYPE_NAMES[ItsMessageId(header.message_id)], uper)


@pytest.mark.parametrize("capture", REAL_CAPTURES)
def test_every_real_packet_heard_twice_is_decoded_once_and_its_mapping_leaves_the_shared_decode_alone(capture):
    codec = V2xPacketCodec()
    mapped = 0
    for frame in read_gn_packets(shared_file(capture)):
        try:
            first = codec.decode_frame(frame.gn_packet)
        except V2xDecodeError:
            continue
        before = copy.deepcopy(first.value)
        try:
            second = codec.decode_packet(frame.gn_packet)
        except V2xDecodeError:
            continue
        assert second.value is first.value
        assert second.value == before
        mapped += 1
    assert mapped > 0


@pytest.mark.parametrize("kind", MAPPINGS)
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(data=st.data())
def test_the_decode_of_any_content_is_the_fresh_decode_and_stays_it_after_mapping(kind, data):
    message_id, content_class, to_asn, from_asn, versions = MAPPINGS[kind]
    content = data.draw(any_message(content_class))
    content.protocol_version = data.draw(st.sampled_from(versions))
    try:
        uper = CODEC.encode(message_id, to_asn(content))
    except V2xEncodeError:
        return
    shared = CODEC.decode(uper)[1]
    assert shared == fresh_decode(uper)
    try:
        from_asn(shared)
    except (ValueError, KeyError, TypeError):
        pass  # refused as unmappable content; what matters is that the decode is untouched
    assert CODEC.decode(uper)[1] is shared
    assert shared == fresh_decode(uper)


def test_the_oldest_decode_is_forgotten_beyond_capacity_and_a_miss_is_counted():
    recent = RecentDecodes(capacity=2)
    for key in (b"a", b"b", b"c"):
        recent.keep(key, {"key": key})
    assert recent.get(b"a") is None
    assert recent.get(b"c") == {"key": b"c"}
    assert (recent.hits, recent.misses) == (1, 1)


def test_undecodable_bytes_are_refused_every_time_and_never_kept():
    garbage = bytes([1, 2, 0, 0, 0, 7]) + b"\xff" * 3
    for _ in range(2):
        with pytest.raises(V2xDecodeError, match="malformed"):
            CODEC.decode(garbage)
