import pytest

from coopdrive.v2x.btp import BtpBHeader, BtpParseError, BtpPort, parse_btp_b
from coopdrive.v2x.geonet import (
    BASIC_HEADER_SIZE, BEACON_HEADER_SIZE, COMMON_HEADER_SIZE, GN_VERSION_GCDC, SHB_HEADER_SIZE, BasicHeader,
    BeaconHeader, CommonHeader, CommonNextHeader, GbcHeader, GeoArea, GeoAreaShape, GnAddress,
    GnPacket, GnParseError, HeaderType, LongPositionVector, ShbHeader, encode_lifetime, parse_gn)
from coopdrive.v2x.reasons import RejectReason

POSITION = LongPositionVector(GnAddress(False, 5, 0, bytes.fromhex("0a0b0c0d0e0f")), 0xFFFFFFFF,
                              -577_089_000, 119_735_000, True, -16_384, 3599)


def shb_packet(payload=b"\x07\xd1\x00\x00hello", version=GN_VERSION_GCDC):
    return GnPacket(BasicHeader(version), CommonHeader(), ShbHeader(POSITION, 0xDEADBEEF), payload)


def test_a_single_hop_broadcast_is_40_header_bytes_and_survives_a_round_trip():
    data = shb_packet().to_bytes()
    assert len(data) == 4 + 8 + SHB_HEADER_SIZE + 9 and SHB_HEADER_SIZE == 28
    assert data[0] == 0x01 and data[5] == 0x50  # version 0 / next header common; HT 5 (TSB) HST 0 (SHB)
    parsed = parse_gn(data)
    assert parsed.extended == ShbHeader(POSITION, 0xDEADBEEF)
    assert parsed.payload == b"\x07\xd1\x00\x00hello"
    assert parsed.common.payload_length == 9 and parsed.common.header_type == HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST


@pytest.mark.parametrize("shape", list(GeoAreaShape))
def test_a_geo_broadcast_keeps_its_area_and_sequence_number(shape):
    area = GeoArea(shape, 577_000_000, -119_000_000, 65_535, 200, 359)
    data = GnPacket(BasicHeader(1), CommonHeader(), GbcHeader(65_535, POSITION, area), b"xy").to_bytes()
    assert data[5] == 0x40 | shape
    parsed = parse_gn(data)
    assert parsed.extended == GbcHeader(65_535, POSITION, area)
    assert parsed.basic.version == 1 and parsed.payload == b"xy"


def test_ethernet_padding_after_the_payload_is_dropped():
    assert parse_gn(shb_packet(b"ab").to_bytes() + bytes(20)).payload == b"ab"


@pytest.mark.parametrize(("data", "reason"), [
    (b"\x01\x00", RejectReason.TRUNCATED_BASIC_HEADER),
    (b"\x31\x00\x01\x01", RejectReason.UNSUPPORTED_GN_VERSION),
    (b"\x12\x00\x01\x01", RejectReason.SECURED_PACKET_UNSUPPORTED),
    (b"\x13\x00\x01\x01", RejectReason.UNKNOWN_BASIC_NEXT_HEADER),
    (b"\x11\x00\x01\x01\x20\x50", RejectReason.TRUNCATED_COMMON_HEADER),
    (b"\x11\x00\x01\x01\x20\x20\x00\x80\x00\x00\x01\x00", RejectReason.UNSUPPORTED_HEADER_TYPE),
    (b"\x11\x00\x01\x01\x20\x50\x00\x80\x00\x00\x01\x00" + bytes(10), RejectReason.TRUNCATED_EXTENDED_HEADER),
])
def test_a_broken_header_is_rejected_with_the_reason_naming_it(data, reason):
    with pytest.raises(GnParseError) as error:
        parse_gn(data)
    assert error.value.reason == reason


def test_a_payload_shorter_than_announced_is_a_length_mismatch():
    data = shb_packet(b"abcdef").to_bytes()[:-2]
    with pytest.raises(GnParseError, match="payload_length_mismatch"):
        parse_gn(data)


def test_only_the_configured_gn_versions_are_accepted():
    with pytest.raises(GnParseError, match="unsupported_gn_version"):
        parse_gn(shb_packet(version=1).to_bytes(), accepted_versions=(GN_VERSION_GCDC,))


def test_a_lifetime_is_encoded_with_the_finest_base_that_holds_it():
    assert encode_lifetime(1.0) == (20, 0)
    assert encode_lifetime(60.0) == (60, 1)
    assert encode_lifetime(100.0) == (10, 2)
    assert encode_lifetime(1e6) == (63, 3)
    assert BasicHeader(lifetime_multiplier=6, lifetime_base=2).lifetime_s == 60.0


def test_btp_b_ports_are_the_etsi_and_gcdc_ones_and_its_header_round_trips():
    assert (BtpPort.CAM, BtpPort.DENM, BtpPort.ICLCM) == (2001, 2002, 2010)
    header, payload = parse_btp_b(BtpBHeader(2010, 7).pack() + b"uper")
    assert header == BtpBHeader(2010, 7) and payload == b"uper"
    with pytest.raises(BtpParseError, match="truncated_btp_header"):
        parse_btp_b(b"\x07")


def test_a_beacon_packs_to_its_position_vector_alone_and_parses_back():
    vector = LongPositionVector(GnAddress(mid=b"\x02\x00\x00\x00\x00\x07"), 1234, 577089000, 119735000)
    packet = GnPacket(BasicHeader(version=0), CommonHeader(next_header=CommonNextHeader.ANY), BeaconHeader(vector),
                      b"").to_bytes()
    assert len(packet) == BASIC_HEADER_SIZE + COMMON_HEADER_SIZE + BEACON_HEADER_SIZE
    parsed = parse_gn(packet)
    assert isinstance(parsed.extended, BeaconHeader) and parsed.extended.source_position == vector
