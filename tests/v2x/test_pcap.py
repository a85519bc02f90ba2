import io
import struct

import pytest

from coopdrive.services.v2x.pcap import (
    ETHERTYPE_GEONETWORKING, LINKTYPE_ETHERNET, PcapFormatError, PcapWriter, parse_ethernet, read_frames,
    read_gn_packets)

SOURCE_MAC = bytes.fromhex("02000000002a")


def written(packets):
    stream = io.BytesIO()
    writer = PcapWriter(stream, SOURCE_MAC)
    for time_s, packet in packets:
        writer.write(packet, time_s)
    stream.seek(0)
    return stream


def test_written_packets_come_back_as_ethernet_frames_from_our_mac_with_the_geonetworking_ethertype():
    frames = list(read_frames(written([(1.25, b"gn-one"), (2.000001, b"gn-two")])))
    assert [frame.time_s for frame in frames] == pytest.approx([1.25, 2.000001])
    assert all(frame.link_type == LINKTYPE_ETHERNET for frame in frames)
    ethernet = parse_ethernet(frames[1].data)
    assert ethernet.source_mac == SOURCE_MAC and ethernet.destination_mac == b"\xff" * 6
    assert ethernet.ethertype == ETHERTYPE_GEONETWORKING == 0x8947 and ethernet.payload == b"gn-two"


def test_a_big_endian_nanosecond_pcap_is_read():
    data = struct.pack(">IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 1) + struct.pack(">IIII", 3, 500_000_000, 2, 2) + b"hi"
    (frame,) = read_frames(io.BytesIO(data))
    assert frame.time_s == 3.5 and frame.data == b"hi"


def pcapng_block(block_type, body):
    body += bytes(-len(body) % 4)
    return struct.pack("<II", block_type, len(body) + 12) + body + struct.pack("<I", len(body) + 12)


def test_a_pcapng_with_nanosecond_resolution_is_read():
    section = pcapng_block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    tsresol_option = struct.pack("<HHB3x", 9, 1, 9) + struct.pack("<HH", 0, 0)
    interface = pcapng_block(1, struct.pack("<HHI", 1, 0, 65535) + tsresol_option)
    timestamp = 7_250_000_000
    packet = pcapng_block(6, struct.pack("<IIIII", 0, timestamp >> 32, timestamp & 0xFFFFFFFF, 5, 5) + b"frame")
    (frame,) = read_frames(io.BytesIO(section + interface + packet))
    assert frame.time_s == pytest.approx(7.25) and frame.data == b"frame" and frame.link_type == 1


@pytest.mark.parametrize("data", [b"", b"\xd4\xc3", b"\x00\x01\x02\x03" + bytes(20)])
def test_a_file_that_is_not_a_capture_is_a_format_error(data):
    with pytest.raises(PcapFormatError):
        list(read_frames(io.BytesIO(data)))


def test_a_capture_cut_inside_a_record_is_a_format_error():
    data = written([(1.0, b"0123456789")]).getvalue()[:-3]
    with pytest.raises(PcapFormatError, match="truncated record"):
        list(read_frames(io.BytesIO(data)))


def test_only_geonetworking_frames_are_returned_as_gn_packets_with_their_source_mac():
    stream = written([(1.0, b"gn-one")])
    other = bytes(6) + SOURCE_MAC + struct.pack(">H", 0x0800) + b"ipv4"
    stream.seek(0, io.SEEK_END)
    stream.write(struct.pack("<IIII", 2, 0, len(other), len(other)) + other)
    stream.seek(0)
    (packet,) = read_gn_packets(stream)
    assert (packet.time_s, packet.source_mac, packet.gn_packet) == (1.0, SOURCE_MAC, b"gn-one")


def test_bare_geonetworking_captures_on_the_user0_link_type_are_read():
    data = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147) + struct.pack("<IIII", 1, 0, 3, 3) + b"\x11gn"
    (packet,) = read_gn_packets(io.BytesIO(data))
    assert packet.source_mac is None and packet.gn_packet == b"\x11gn"
