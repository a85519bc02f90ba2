"""NMEA logs into gnss/nmea chunks: the receiver's UTC gives the times, every line but comments is kept."""

import datetime as dt

import pytest

from coopdrive.recording.import_source import ImportFailure
from coopdrive.recording.nmea_import import read_nmea_log
from tests.shared_data import shared_file

GOOD_GGA = b"$GPGGA,094736,5251.0094,N,00518.8172,E,1,12,0.60,-4,M,46.8,M,,*4B\n"
GOOD_RMC = b"$GPRMC,094737,A,5251.0093,N,00518.8170,E,5.6,230.5,200818,1.4,E,A*1F\n"


def sentence(body: str) -> bytes:
    checksum = 0
    for char in body.encode():
        checksum ^= char
    return f"${body}*{checksum:02X}\r\n".encode()


def utc(text: str) -> float:
    return dt.datetime.fromisoformat(text).replace(tzinfo=dt.timezone.utc).timestamp()


def test_a_real_log_becomes_one_chunk_per_sentence_timed_by_its_utc_and_date():
    path = shared_file("gnss/gpsd_bundg_zeus_9.log")
    report = read_nmea_log(path)
    sentences = [line for line in path.read_bytes().splitlines(keepends=True) if not line.startswith(b"#")]
    assert [m.message.data for m in report.messages] == sentences
    assert not report.bad
    first_gga = next(m for m in report.messages if m.message.data.startswith(b"$GPGGA"))
    # 09:47:36 UTC on the RMC's date 20 Aug 2018, though the first RMC comes after the first GGA.
    assert first_gga.time_s == pytest.approx(utc("2018-08-20T09:47:36"), abs=0.05)
    times = [m.time_s for m in report.messages]
    assert times == sorted(times) and len(set(times)) == len(times)
    assert all(m.message.port == path.name for m in report.messages)


def test_zda_gives_the_date_of_a_log_without_rmc():
    report = read_nmea_log(shared_file("gnss/gpsd_hemi.log"))
    assert report.first_s == pytest.approx(utc("2018-09-07T19:39:13"), abs=0.05)


def test_truncated_lines_bad_checksums_and_binary_junk_are_counted_per_reason_and_nothing_is_lost(tmp_path):
    path = tmp_path / "bad.nmea"
    truncated = b"$GPGGA,094737,5251.0085,N,0051\n"
    bad_checksum = GOOD_GGA.replace(b"*4B", b"*00")
    junk = b"\xb5\x62\x01\x07\x5c\x00\xff\xfe\n"
    cut_then_whole = b"$GPRMC,0947" + GOOD_RMC
    path.write_bytes(b"# a gpsd comment\n" + GOOD_GGA + truncated + bad_checksum + junk + b"hello\n" + cut_then_whole)
    report = read_nmea_log(path)
    assert dict(report.bad) == {"truncated": 2, "bad_checksum": 1, "binary_junk": 1, "not_nmea": 1}
    data = [m.message.data for m in report.messages]
    # Every byte but the comment reaches the recording, and the whole RMC after the cut one is its own chunk.
    assert b"".join(data) == GOOD_GGA + truncated + bad_checksum + junk + b"hello\n" + cut_then_whole
    assert GOOD_RMC in data
    assert "2 truncated" in report.summary_line() and "1 binary_junk" in report.summary_line()


def test_a_log_without_utc_needs_a_rate_and_then_gets_one_epoch_per_position_sentence(tmp_path):
    path = tmp_path / "no_time.nmea"
    gga_without_time = sentence("GPGGA,,5251.0094,N,00518.8172,E,1,12,0.60,-4,M,46.8,M,,")
    path.write_bytes(sentence("GPGSA,A,3,,,,,,,,,,,,,1.0,0.6,0.8") + gga_without_time * 3)
    with pytest.raises(ImportFailure, match="no UTC time.*--nmea-rate"):
        read_nmea_log(path)
    times = [m.time_s for m in read_nmea_log(path, rate_hz=5.0).messages]
    assert times == pytest.approx([0.0, 0.001, 0.2, 0.4])
