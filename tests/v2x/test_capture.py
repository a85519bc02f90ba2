import io
import struct

import dpkt
import pytest

from coopdrive.recording.capture import (
    MALFORMED_FRAME, NOT_A_DATA_FRAME, NOT_LLC_SNAP, OTHER_ETHERTYPE, UNSUPPORTED_LINK_TYPE, CaptureFormatError,
    read_capture, read_gn_packets)
from tests.shared_data import shared_file
from tests.v2x.capture_wrap import RADIOTAP_EMPTY, wrap_capture, wrapped

SIGNED = "v2x/considerit_signed_testvectors.pcap"
SOURCE_MAC = bytes.fromhex("02000000002a")


def capture(link_type: int, frames: list[bytes], nano: bool = False) -> io.BytesIO:
    stream = io.BytesIO()
    writer = dpkt.pcap.Writer(stream, snaplen=65535, linktype=link_type, nano=nano)
    for number, frame in enumerate(frames):
        writer.writepkt(frame, 1.5 + number)
    stream.seek(0)
    return stream


def test_every_frame_of_the_real_signed_capture_is_an_ethernet_geonetworking_packet_with_its_time_and_mac():
    frames = list(read_capture(shared_file(SIGNED)))
    assert [frame.index for frame in frames] == [0, 1, 2, 3]
    assert [frame.time_s for frame in frames] == [1700000000.0, 1700000001.0, 1700000002.0, 1700000003.0]
    assert {(frame.link_type, frame.ethertype, frame.source_mac) for frame in frames} == {
        ("ethernet", 0x8947, bytes.fromhex("020000000001"))}
    assert all(frame.gn_packet[0] >> 4 == 1 and frame.unreadable is None for frame in frames)


def test_a_pcapng_named_capture_that_is_really_pcap_is_read_by_its_magic_number():
    assert sum(1 for _ in read_gn_packets(shared_file("v2x/msvan3t_cam_cpm_trace.pcapng"))) == 929


@pytest.mark.parametrize("link_type", ["ieee802_11", "radiotap", "linux_sll", "linux_sll2"])
def test_the_signed_capture_rewrapped_in_another_link_type_gives_the_same_packets_and_macs(tmp_path, link_type):
    original = list(read_capture(shared_file(SIGNED)))
    rewrapped = list(read_capture(wrap_capture(shared_file(SIGNED), tmp_path / "w.pcap", link_type)))
    assert [frame.link_type for frame in rewrapped] == [link_type] * 4
    assert [(f.gn_packet, f.source_mac) for f in rewrapped] == [(f.gn_packet, f.source_mac) for f in original]
    assert [f.time_s for f in rewrapped] == pytest.approx([f.time_s for f in original])


def test_a_pcapng_file_is_read_with_its_timestamps():
    stream = io.BytesIO()
    writer = dpkt.pcapng.Writer(stream, linktype=1)
    writer.writepkt(wrapped("ethernet", SOURCE_MAC, b"\x11gn"), ts=7.25)
    stream.seek(0)
    (frame,) = read_capture(stream)
    assert frame.time_s == pytest.approx(7.25) and frame.gn_packet == b"\x11gn" and frame.source_mac == SOURCE_MAC


def test_frames_of_another_ethertype_are_counted_not_dropped():
    ipv4 = b"\xff" * 6 + SOURCE_MAC + struct.pack(">H", 0x0800) + b"ipv4"
    frames = list(read_capture(capture(1, [wrapped("ethernet", SOURCE_MAC, b"\x11gn"), ipv4])))
    assert frames[0].gn_packet == b"\x11gn"
    assert (frames[1].unreadable, frames[1].detail, frames[1].ethertype) == (OTHER_ETHERTYPE, "0x0800", 0x0800)


def test_802_11_management_frames_and_non_snap_data_are_named_as_such():
    beacon = RADIOTAP_EMPTY + b"\x80\x00" + bytes(2) + b"\xff" * 6 + SOURCE_MAC * 2 + bytes(2) + bytes(12)
    non_snap = RADIOTAP_EMPTY + wrapped("ieee802_11", SOURCE_MAC, b"")[:24 + 2] + b"\x42\x42\x03stp"
    frames = list(read_capture(capture(127, [beacon, non_snap])))
    assert frames[0].unreadable == NOT_A_DATA_FRAME
    assert (frames[1].unreadable, frames[1].source_mac) == (NOT_LLC_SNAP, SOURCE_MAC)


def test_a_frame_too_short_for_its_link_header_is_malformed_and_reading_goes_on():
    frames = list(read_capture(capture(1, [b"\x01\x02", wrapped("ethernet", SOURCE_MAC, b"\x11gn")])))
    assert frames[0].unreadable == MALFORMED_FRAME and frames[1].gn_packet == b"\x11gn"


def test_a_link_type_we_do_not_read_is_named_for_every_frame():
    frames = list(read_capture(capture(228, [b"\x45\x00", b"\x45\x00"])))  # raw IPv4
    assert [(frame.link_type, frame.unreadable) for frame in frames] == [("dlt_228", UNSUPPORTED_LINK_TYPE)] * 2


def test_bare_geonetworking_on_user0_is_read_without_a_mac():
    (frame,) = read_capture(capture(147, [b"\x11gn"], nano=True))
    assert (frame.link_type, frame.source_mac, frame.gn_packet, frame.time_s) == ("bare_gn", None, b"\x11gn", 1.5)


@pytest.mark.parametrize("data", [b"", b"\xd4\xc3", b"\x00\x01\x02\x03" + bytes(20)])
def test_a_file_that_is_not_a_capture_is_a_format_error(data):
    with pytest.raises(CaptureFormatError):
        list(read_capture(io.BytesIO(data)))
