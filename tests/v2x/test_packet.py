import math
import struct

import pytest

from coopdrive.v2x.geonet import CommonNextHeader, ShbHeader
from coopdrive.v2x.packet import (
    GnParams, SourcePosition, decode_packet, encode_cam, encode_denm, encode_iclcm)
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v1 import its_pb2

from .messages import denm, iclcm

MAC = bytes.fromhex("02000000002a")
BTP_OFFSET_IN_SHB = 40


def moving_cam() -> its_pb2.CamContent:
    content = its_pb2.CamContent(protocol_version=1, station_id=77)
    content.reference_position.latitude_deg = 51.4500001
    content.reference_position.longitude_deg = -5.48
    content.high_frequency.speed_mps = 13.89
    content.high_frequency.heading_rad = math.pi  # west
    return content


def test_a_cam_fills_the_gn_position_vector_from_its_own_position_speed_and_heading():
    params = GnParams(source_mac=MAC, station_type=8, time_tai_ms=2**32 + 5, lifetime_s=1.0)
    decoded = decode_packet(encode_cam(moving_cam(), params))
    assert decoded.message_type == ItsMessageId.CAM and decoded.btp.destination_port == 2001
    vector = decoded.gn.extended.source_position
    assert vector.address.mid == MAC and vector.address.station_type == 8
    assert vector.timestamp_ms == 5  # TAI ms mod 2^32
    assert (vector.latitude_tenth_microdeg, vector.longitude_tenth_microdeg) == (514_500_001, -54_800_000)
    assert vector.speed_cmps == 1389 and vector.heading_tenth_deg == 2700
    assert decoded.gn.basic.version == 0 and decoded.gn.basic.lifetime_s == 1.0


def test_an_iclcm_travels_single_hop_on_port_2010():
    params = GnParams(source_mac=MAC, source_position=SourcePosition(57.7, 11.9))
    decoded = decode_packet(encode_iclcm(iclcm(True), params))
    assert decoded.message_type == ItsMessageId.ICLCM and decoded.btp.destination_port == 2010
    assert isinstance(decoded.gn.extended, ShbHeader) and decoded.content.merge_flag_head


def test_a_denm_needs_a_source_position_to_be_sent():
    with pytest.raises(ValueError, match="source_position"):
        encode_denm(denm(False), GnParams(source_mac=MAC))


def test_a_cam_on_the_iclcm_port_is_a_message_id_port_mismatch():
    packet = bytearray(encode_cam(moving_cam(), GnParams(source_mac=MAC)))
    struct.pack_into(">H", packet, BTP_OFFSET_IN_SHB, 2010)
    with pytest.raises(V2xDecodeError) as error:
        decode_packet(bytes(packet))
    assert error.value.reason == RejectReason.MESSAGE_ID_PORT_MISMATCH


def test_a_btp_a_packet_is_refused_as_not_btp_b():
    packet = bytearray(encode_cam(moving_cam(), GnParams(source_mac=MAC)))
    packet[4] = CommonNextHeader.BTP_A << 4
    with pytest.raises(V2xDecodeError) as error:
        decode_packet(bytes(packet))
    assert error.value.reason == RejectReason.NOT_BTP_B


def test_a_v2_cam_decodes_with_the_v2_schema():
    content = moving_cam()
    content.protocol_version = 2
    content.high_frequency.curvature_per_m = 0.05
    decoded = decode_packet(encode_cam(content, GnParams(source_mac=MAC, gn_version=1)))
    assert decoded.its_header.protocol_version == 2 and decoded.gn.basic.version == 1
    assert decoded.content.high_frequency.curvature_per_m == pytest.approx(0.05)


def test_a_content_message_with_protocol_version_left_unset_is_sent_as_gcdc_version_1():
    content = moving_cam()
    content.ClearField("protocol_version")
    decoded = decode_packet(encode_cam(content, GnParams(source_mac=MAC)))
    assert decoded.its_header.protocol_version == 1 and decoded.content.protocol_version == 1
