"""Radiotap as radiotap.org defines it: a monitor capture with the FCS kept, with the 802.11 header padded, behind
extended present words, decodes exactly like the same real packets without; a frame that failed its FCS is
counted as bad_fcs and not read. Wireshark reads the frames we build the same way (its FCS check included)."""

import json
import subprocess

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coopdrive.recording.capture import BAD_FCS, read_capture
from coopdrive.recording.radiotap import RadiotapError, read_radiotap
from coopdrive.services.v2x.capture_decode import decode_capture
from tests.recording.radiotap_frames import FCS_BAD, FCS_KEPT, FCS_KEPT_AND_PADDED, write_monitor_capture
from tests.system_packages import require

SIGNED_VECTORS = "v2x/considerit_signed_testvectors.pcap"


def decoded(path) -> list[dict]:
    """Each frame's decode, less what says how it was captured."""
    lines = [json.loads(line) for line in decode_capture(path, as_json=True)]
    frames = [line for line in lines if "summary" not in line]
    for frame in frames:
        frame.pop("link_type")
    return frames


@pytest.mark.parametrize("flags", [None, FCS_KEPT, FCS_KEPT_AND_PADDED], ids=["plain", "fcs", "fcs-padded"])
def test_a_monitor_capture_decodes_exactly_like_the_same_real_packets_over_ethernet(shared_data, tmp_path, flags):
    monitor = tmp_path / "monitor.pcap"
    write_monitor_capture(shared_data / SIGNED_VECTORS, monitor, flags)
    ours = decoded(monitor)
    assert ours == decoded(shared_data / SIGNED_VECTORS)
    assert sum(frame["security"]["verified"] is True for frame in ours) == 3


def test_a_frame_that_failed_its_fcs_is_counted_and_not_read(shared_data, tmp_path):
    monitor = tmp_path / "bad-fcs.pcap"
    write_monitor_capture(shared_data / SIGNED_VECTORS, monitor, FCS_BAD)
    frames = list(read_capture(monitor))
    assert [frame.unreadable for frame in frames] == [BAD_FCS] * 4
    assert all(frame.gn_packet is None for frame in frames)


def wireshark_fcs_status_and_station(path) -> list[tuple[str, str]]:
    result = subprocess.run([require("tshark"), "-r", str(path), "-o", "wlan.check_checksum:TRUE", "-T", "fields",
                             "-e", "wlan.fcs.status", "-e", "its.stationID"],
                            check=True, capture_output=True, text=True, timeout=60)
    return [tuple(line.split("\t")) for line in result.stdout.splitlines()]


def test_wireshark_finds_our_fcs_good_the_flipped_one_bad_and_the_same_stations(shared_data, tmp_path):
    good, bad = tmp_path / "good.pcap", tmp_path / "bad.pcap"
    write_monitor_capture(shared_data / SIGNED_VECTORS, good, FCS_KEPT_AND_PADDED)
    write_monitor_capture(shared_data / SIGNED_VECTORS, bad, FCS_BAD)
    assert wireshark_fcs_status_and_station(good) == [("1", ""), ("1", "3141730734"), ("1", "12816437"),
                                                      ("1", "10430022")]  # 1: good, 0: bad
    assert [status for status, _ in wireshark_fcs_status_and_station(bad)] == ["0"] * 4


@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=64))
def test_any_bytes_as_a_radiotap_header_give_a_header_or_a_radiotap_error(data):
    try:
        header = read_radiotap(data)
    except RadiotapError:
        return
    assert 8 <= header.length <= len(data)
