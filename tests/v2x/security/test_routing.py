"""The small changes outside security/: the basic header parser and the envelope swap of geonet, the report."""

import io

import pytest

from coopdrive.v2x.geonet import BasicNextHeader, parse_basic_header, parse_gn, with_basic_next_header
from coopdrive.v2x.packet import GnParams
from coopdrive.v2x.pcap import PcapWriter
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.services.v2x.capture_decode import CaptureDecoder

from .signed import CODEC, cam, cam_packet

MAC = bytes.fromhex("02000000002a")


def test_the_basic_header_parser_accepts_common_and_secured_next_headers_and_names_anything_else():
    assert parse_basic_header(b"\x12\x00\x05\x01").next_header == BasicNextHeader.SECURED_PACKET
    assert parse_basic_header(b"\x01\x00\x05\x01").next_header == BasicNextHeader.COMMON_HEADER
    for data, reason in ((b"\x12\x00", RejectReason.TRUNCATED_BASIC_HEADER),
                         (b"\x32\x00\x05\x01", RejectReason.UNSUPPORTED_GN_VERSION),
                         (b"\x13\x00\x05\x01", RejectReason.UNKNOWN_BASIC_NEXT_HEADER)):
        with pytest.raises(V2xDecodeError) as error:
            parse_basic_header(data)
        assert error.value.reason == reason


def test_swapping_the_next_header_keeps_version_lifetime_and_hop_limit(p256_pki):
    packet = cam_packet(p256_pki.signer("a"))
    secured = with_basic_next_header(packet, BasicNextHeader.SECURED_PACKET, b"envelope")
    assert secured[0] == (packet[0] & 0xF0) | 2 and secured[1:4] == packet[1:4] and secured[4:] == b"envelope"
    assert with_basic_next_header(secured, BasicNextHeader.COMMON_HEADER, packet[4:]) == packet
    assert parse_gn(packet).basic == parse_gn(with_basic_next_header(secured, BasicNextHeader.COMMON_HEADER,
                                                                     packet[4:])).basic


def test_the_report_lists_an_unsigned_packet_as_unsigned():
    stream = io.BytesIO()
    PcapWriter(stream, MAC).write(CODEC.encode_cam(cam(7), GnParams(source_mac=MAC)), 1.0)
    stream.seek(0)
    (row,) = CaptureDecoder().records(stream)
    security = row["security"]
    assert (row["message_type"], security["signed"], security["signer_digest"], security["verified"],
            security["reason"]) == ("cam", False, None, None, None)
