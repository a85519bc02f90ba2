import io

import pytest

from coopdrive.recording.capture import read_capture
from coopdrive.recording.link_types import ETHERTYPE_GEONETWORKING
from coopdrive.v2x.pcap import PcapWriter

SOURCE_MAC = bytes.fromhex("02000000002a")


def written(packets):
    stream = io.BytesIO()
    writer = PcapWriter(stream, SOURCE_MAC)
    for time_s, packet in packets:
        writer.write(packet, time_s)
    stream.seek(0)
    return stream


def test_written_packets_come_back_as_ethernet_frames_from_our_mac_with_the_geonetworking_ethertype():
    frames = list(read_capture(written([(1.25, b"gn-one"), (2.000001, b"gn-two")])))
    assert [frame.time_s for frame in frames] == pytest.approx([1.25, 2.000001])
    assert all(frame.link_type == "ethernet" for frame in frames)
    assert frames[1].source_mac == SOURCE_MAC
    assert frames[1].ethertype == ETHERTYPE_GEONETWORKING == 0x8947 and frames[1].gn_packet == b"gn-two"


def test_mac_addresses_other_than_six_bytes_are_refused():
    with pytest.raises(ValueError, match="6 bytes"):
        PcapWriter(io.BytesIO(), b"\x02")
