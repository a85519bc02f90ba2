"""`coopdrive import` and `coopdrive export` as a user runs them, on the real logs."""

import csv
import io
import json
import subprocess
import sys

import pytest

from coopdrive.recording.reader import read_messages, read_metadata
from coopdrive.recording.flatten import flatten
from coopdrive.v1 import ego_pb2, gnss_pb2
from tests.shared_data import shared_file


def coopdrive(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def drive(tmp_path_factory):
    out = tmp_path_factory.mktemp("import") / "drive.mcap"
    result = coopdrive("import", "--out", str(out), "--vehicle", "boat",
                       "--nmea", str(shared_file("gnss/gpsd_hemi.log")),
                       "--candump", str(shared_file("can/comma2k19_rav4_bus0_first20s.candump.log")),
                       "--can-bus", "powertrain", "--offset", "candump=1536302745",
                       "--pcap", str(shared_file("v2x/considerit_signed_testvectors.pcap")))
    assert result.returncode == 0, result.stderr
    return out, result.stdout


def test_the_import_summary_names_each_log_its_counts_and_the_logs_that_do_not_overlap(drive):
    _, summary = drive
    assert "nmea gpsd_hemi.log: 753 read, 753 messages" in summary
    assert "candump comma2k19_rav4_bus0_first20s.candump.log: 17938 read" in summary
    assert "(shifted +1536302745.000 s)" in summary
    assert "considerit_signed_testvectors.pcap do not overlap in time" in summary
    assert "wrote " in summary


def test_an_imported_recording_holds_the_topics_of_its_vehicle_on_one_time_base_and_default_configs(drive):
    out, _ = drive
    messages = list(read_messages(out))
    assert {m.topic for m in messages} == {"coopdrive/boat/gnss/nmea", "coopdrive/boat/can/powertrain",
                                           "coopdrive/boat/v2x/rx"}
    log_times = [m.log_time_ns for m in messages]
    assert log_times == sorted(log_times)
    assert all(m.message.header.sent_time_s * 1e9 == pytest.approx(m.log_time_ns, abs=2e3) for m in messages)
    metadata = read_metadata(out)
    assert "boat/geolocation" in metadata["coopdrive.config"]
    assert metadata["coopdrive.config_source"]["boat/geolocation"] == "default"
    assert metadata["coopdrive.import"]["start_utc"].startswith("2018-09-07T")


def test_an_offset_for_a_log_that_was_not_imported_is_refused_naming_the_logs(tmp_path):
    result = coopdrive("import", "--out", str(tmp_path / "x.mcap"), "--nmea", str(shared_file("gnss/gpsd_hemi.log")),
                       "--offset", "pcap=3")
    assert result.returncode == 2
    assert "--offset pcap: no imported log of that name (there are: gpsd_hemi.log, nmea)" in result.stderr


def test_export_writes_one_csv_row_per_message_with_dotted_names_to_standard_output(drive):
    out, _ = drive
    result = coopdrive("export", str(out), "--topic", "gnss/nmea")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert len(rows) == 753
    assert {"log_time_s", "vehicle", "header.sample_time_s", "header.sequence", "data", "port"} <= set(rows[0])
    assert rows[0]["vehicle"] == "boat" and rows[0]["port"] == "gpsd_hemi.log"


def test_export_as_json_lines_to_a_file_and_an_unknown_topic_names_the_recorded_ones(drive, tmp_path):
    out, _ = drive
    target = tmp_path / "can.jsonl"
    assert coopdrive("export", str(out), "--topic", "can/powertrain", "--format", "jsonl", "--out", str(target)
                     ).returncode == 0
    first = json.loads(target.read_text().splitlines()[0])
    assert json.loads(first["frames"])[0]["arbitration_id"] == 0x260  # repeated fields: JSON text
    missing = coopdrive("export", str(out), "--topic", "ego/state", "--vehicle", "boat")
    assert missing.returncode == 2
    assert "no messages of vehicle 'boat', topic 'ego/state'; recorded: boat/can/powertrain" in missing.stderr


def test_export_takes_a_topic_as_the_recorded_list_names_it_with_its_vehicle_first(drive):
    out, _ = drive
    result = coopdrive("export", str(out), "--topic", "boat/gnss/nmea")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert len(rows) == 753 and {row["vehicle"] for row in rows} == {"boat"}


def test_flattening_names_enums_as_text_and_nests_with_dots():
    state = ego_pb2.EgoState(x_m=1.5, last_fix_mode=gnss_pb2.FIX_MODE_RTK_FIXED, covariance=[1.0, 2.0])
    state.header.sample_time_s = 3.25
    row = flatten(state)
    assert row["header.sample_time_s"] == 3.25 and row["x_m"] == 1.5
    assert row["last_fix_mode"] == "FIX_MODE_RTK_FIXED"
    assert row["covariance"] == "[1.0, 2.0]"
    assert any(key.startswith("lane.") for key in row)
