"""candump logs into CanFrames batches and V2X captures into v2x/rx packets, at the logs' own times."""

import pytest

from coopdrive.recording.candump_import import BATCH_S, read_candump_log
from coopdrive.recording.import_source import ImportFailure
from coopdrive.recording.pcap_import import read_pcap
from tests.shared_data import shared_file

RAV4_LOG = "can/comma2k19_rav4_bus0_first20s.candump.log"


def test_every_frame_of_the_rav4_log_is_imported_with_its_log_time_in_batches_of_10_ms():
    path = shared_file(RAV4_LOG)
    report = read_candump_log(path)
    frames = [frame for m in report.messages for frame in m.message.frames]
    lines = [line for line in path.read_text().splitlines() if line.strip()]
    assert len(frames) == len(lines) == report.items_read and not report.bad
    assert frames[0].timestamp_s == pytest.approx(46408.584930) and frames[0].arbitration_id == 0x260
    wheel_speeds = next(f for f in frames if f.arbitration_id == 0x0AA)
    assert wheel_speeds.timestamp_s == pytest.approx(46408.589503)
    assert wheel_speeds.data == bytes.fromhex("25B525B525A0258D")
    for message in report.messages:
        times = [frame.timestamp_s for frame in message.message.frames]
        assert max(times) - min(times) < BATCH_S and message.time_s == max(times)
        assert message.topic == "can/vehicle"


def test_bad_candump_lines_are_counted_and_unknown_ids_kept(tmp_path):
    path = tmp_path / "bad.log"
    path.write_bytes(b"(1.000000) can0 0AA#25B525B525A0258D\n"
                     b"(1.001000) can0 7FF#0102\n"  # an id no DBC of ours knows: kept
                     b"(1.002000) can0 0AA#25B52\n"  # cut mid-byte
                     b"\x00\xff\xfe junk\n"
                     b"(1.003000) can0\n"
                     b"(1.004000) can0 12345678#DEADBEEF\n")
    report = read_candump_log(path, bus="chassis")
    frames = [frame for m in report.messages for frame in m.message.frames]
    assert [f.arbitration_id for f in frames] == [0x0AA, 0x7FF, 0x12345678]
    assert frames[2].is_extended_id
    assert dict(report.bad) == {"odd_hex_digits": 1, "binary_junk": 1, "not_candump": 1}
    assert {m.topic for m in report.messages} == {"can/chassis"}


def test_a_pcapng_named_capture_of_real_cams_and_cpms_gives_every_packet_at_its_capture_time():
    report = read_pcap(shared_file("v2x/msvan3t_cam_cpm_trace.pcapng"))
    assert len(report.messages) == report.items_read == 929 and not report.bad
    assert report.first_s == pytest.approx(1726061434.093, abs=0.001)
    packet = report.messages[0].message
    assert packet.payload[0] >> 4 == 1  # GeoNetworking basic header, version 1 (ms-van3t speaks GN v1)


def test_the_signed_test_vectors_keep_the_sender_mac_and_a_file_that_is_no_capture_is_one_error(tmp_path):
    report = read_pcap(shared_file("v2x/considerit_signed_testvectors.pcap"))
    assert [m.time_s for m in report.messages] == [1700000000.0, 1700000001.0, 1700000002.0, 1700000003.0]
    assert report.messages[1].message.source_mac == bytes.fromhex("020000000001")
    junk = tmp_path / "junk.pcap"
    junk.write_bytes(b"not a capture at all")
    with pytest.raises(ImportFailure, match="junk.pcap: not a pcap or pcapng capture"):
        read_pcap(junk)


def test_a_capture_from_an_802_11_monitor_interface_imports_the_same_packets(tmp_path):
    from tests.v2x.capture_wrap import wrap_capture

    original = read_pcap(shared_file("v2x/considerit_signed_testvectors.pcap"))
    radiotap = read_pcap(wrap_capture(shared_file("v2x/considerit_signed_testvectors.pcap"),
                                      tmp_path / "radiotap.pcap", "radiotap"))
    assert [m.message.payload for m in radiotap.messages] == [m.message.payload for m in original.messages]
    assert [m.message.source_mac for m in radiotap.messages] == [m.message.source_mac for m in original.messages]
    assert not radiotap.bad
