"""A CAN frame keeps its own time, shifted by its log's --offset (of either sign), through import and replay."""

import pytest

from coopdrive.recording.reader import read_messages
from coopdrive.recording.replay import replay_service
from coopdrive.services.geolocation.geolocator import Geolocator
from tests.command_line import coopdrive
from tests.shared_data import shared_file

RAV4_LOG = "can/comma2k19_rav4_bus0_first20s.candump.log"
RAV4_NMEA = "gnss/comma2k19_rav4_ublox_first20s.nmea"
RAV4_ADAPTER = "deploy/vehicles/toyota_rav4_2017.yaml"
# The data set's offset from the logger's monotonic clock to UTC (shared/data/README.md).
LOGGER_TO_UTC_S = 1533180079.849502
WHEEL_SPEEDS = 0x0AA


def logged_times_s(arbitration_id: int | None = None) -> list[float]:
    """Each frame's time as the candump line gives it, in log order."""
    times = []
    for line in shared_file(RAV4_LOG).read_text().splitlines():
        stamp, _, frame = line.split()
        if arbitration_id is None or int(frame.partition("#")[0], 16) == arbitration_id:
            times.append(float(stamp[1:-1]))
    return times


def test_a_negative_offset_shifts_every_imported_frame_s_own_time_and_its_batch_s(tmp_path):
    out = tmp_path / "drive.mcap"
    result = coopdrive("import", "--out", str(out), "--candump", str(shared_file(RAV4_LOG)), "--offset", "candump=-0.12")
    assert result.returncode == 0, result.stderr
    assert "(shifted -0.120 s)" in result.stdout
    batches = [m for m in read_messages(out) if m.topic.endswith("/can/vehicle")]
    frame_times_s = [frame.timestamp_s for batch in batches for frame in batch.message.frames]
    assert frame_times_s == pytest.approx([t - 0.12 for t in logged_times_s()], abs=1e-9)
    for batch in batches:  # each batch arrives with its last frame
        assert batch.log_time_ns / 1e9 == pytest.approx(batch.message.frames[-1].timestamp_s, abs=1e-6)


def test_a_wheel_speed_frame_s_own_time_survives_import_and_replay_on_the_receiver_s_clock(tmp_path, monkeypatch):
    out = tmp_path / "drive.mcap"
    result = coopdrive("import", "--out", str(out), "--nmea", str(shared_file(RAV4_NMEA)),
                       "--candump", str(shared_file(RAV4_LOG)), "--offset", f"candump={LOGGER_TO_UTC_S}")
    assert result.returncode == 0, result.stderr
    seen_s = []
    on_can_state = Geolocator.on_can_state

    def spy(self, msg):
        seen_s.append(msg.header.sample_time_s)
        return on_can_state(self, msg)

    monkeypatch.setattr(Geolocator, "on_can_state", spy)
    replay_service(out, "geolocation", overrides=[f"vehicle_can={RAV4_ADAPTER}", "can_latency_s=0"])
    expected_s = [t + LOGGER_TO_UTC_S for t in logged_times_s(WHEEL_SPEEDS)]
    assert len(seen_s) == len(expected_s)
    # Microseconds: what a float of Unix seconds holds; a frame restamped to its batch's arrival is up to 10 ms off.
    assert seen_s == pytest.approx(expected_s, abs=2e-6)
