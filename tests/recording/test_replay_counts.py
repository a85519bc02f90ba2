"""`coopdrive replay` says what the service did with its inputs: counters at the end, and a warning for the car's
CAN frames replayed without the car's adapter (every frame ignored)."""

import json

import pytest

from tests.command_line import coopdrive
from tests.shared_data import shared_file

RAV4_ADAPTER = "deploy/vehicles/toyota_rav4_2017.yaml"
LOGGER_TO_UTC_S = 1533180079.849502  # shared/data/README.md
RAV4_FRAMES = 17938


@pytest.fixture(scope="module")
def drive(tmp_path_factory):
    out = tmp_path_factory.mktemp("counts") / "drive.mcap"
    result = coopdrive("import", "--out", str(out), "--nmea", str(shared_file("gnss/comma2k19_rav4_ublox_first20s.nmea")),
                       "--candump", str(shared_file("can/comma2k19_rav4_bus0_first20s.candump.log")),
                       "--offset", f"candump={LOGGER_TO_UTC_S}")
    assert result.returncode == 0, result.stderr
    return out


def test_a_replay_with_the_car_s_adapter_counts_frames_used_and_ignored_and_updates_refused_by_the_gate(drive):
    result = coopdrive("replay", str(drive), "--service", "geolocation", "--set", f"vehicle_can={RAV4_ADAPTER}")
    assert result.returncode == 0, result.stderr
    assert "geolocation counted:" in result.stdout
    can_line = next(line for line in result.stdout.splitlines() if "CAN frames:" in line)
    assert f"CAN frames: {RAV4_FRAMES} received, " in can_line and "ids the adapter does not use" in can_line
    assert "odometry updates: " in result.stdout and "beyond the gate" in result.stdout
    assert "nmea_fixes 192" in result.stdout
    assert "warning" not in result.stderr


def test_a_replay_without_the_car_s_adapter_warns_that_every_can_frame_was_ignored(drive):
    result = coopdrive("replay", str(drive), "--service", "geolocation")
    assert result.returncode == 0, result.stderr
    assert (f"coopdrive: replay: warning: geolocation ignored all {RAV4_FRAMES} CAN frames (90 ids): its vehicle CAN "
            f"adapter uses none of them; give the car's with --set vehicle_can=FILE") in result.stderr
    assert f"CAN frames: {RAV4_FRAMES} received, 0 used, {RAV4_FRAMES} ignored" in result.stdout


def test_replay_json_holds_the_counters_and_a_fix_fused_again_after_a_late_input_counts_once(drive):
    result = coopdrive("replay", str(drive), "--service", "geolocation", "--set", f"vehicle_can={RAV4_ADAPTER}",
                       "--json")
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    counters = summary["counters"]
    assert summary["warnings"] == []
    assert counters["insertion_replayed"] > 0  # late CAN frames made the filter fuse fixes again
    assert counters["input_fix_fused"] + counters.get("input_fix_gated", 0) == counters["nmea_fixes"] == 192


def test_a_value_the_service_estimated_is_one_line_with_its_std():
    from coopdrive.recording.replay_counts import counter_lines

    assert counter_lines({"estimated_wheel_scale": 1.0106, "estimated_wheel_scale_std": 0.00048, "nmea_fixes": 192}) == [
        "estimated wheel scale: 1.0106 +- 0.00048 (1 sigma)", "nmea_fixes 192"]
