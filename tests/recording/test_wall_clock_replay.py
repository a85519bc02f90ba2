"""Replay of recordings without a lockstep clock: inputs in arrival order, time triggers on a clock they drive."""

import datetime as dt
import json
import subprocess
import sys

import pymap3d
import pynmea2
import pytest

from coopdrive.bus import KeyLayout
from coopdrive.recording.reader import RecordedMessage, read_messages
from coopdrive.recording.replay import ReplayContext, replay_service
from coopdrive.recording.replay_wall import run_wall_clock
from coopdrive.bus.publish_spool import NANOSECONDS
from coopdrive.recording.writer import McapRecorder, config_metadata
from coopdrive.geodesy import GeodeticOrigin
from coopdrive.services.geolocation.service import GeolocationConfig
from coopdrive.v1 import gnss_pb2, v2x_pb2

START_S = 1_700_000_000.0
FIX_PERIOD_S = 0.1
FIXES = 40
SPEED_MPS = 10.0
ARRIVAL_DELAY_S = 0.03


def coopdrive(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=120)


def fix_at(time_s: float) -> gnss_pb2.GnssFix:
    origin = GeodeticOrigin()
    lat, lon, alt = pymap3d.enu2geodetic(SPEED_MPS * (time_s - START_S), 0.0, 0.0,
                                         origin.lat_deg, origin.lon_deg, origin.alt_m)
    fix = gnss_pb2.GnssFix(latitude_deg=lat, longitude_deg=lon, altitude_m=alt, fix_mode=gnss_pb2.FIX_MODE_RTK_FIXED,
                           speed_mps=SPEED_MPS, course_deg=90.0, satellites=12, hdop=0.6)
    fix.header.sent_time_s = fix.header.sample_time_s = time_s
    fix.header.vehicle_id, fix.header.sender, fix.header.sequence = "ego", "sim", 1
    return fix


def nmea_of(fix: gnss_pb2.GnssFix) -> list[gnss_pb2.NmeaChunk]:
    """The same fix as a receiver's GGA and RMC sentences (RTK fixed, speed in knots)."""
    when = dt.datetime.fromtimestamp(fix.header.sample_time_s, dt.timezone.utc)
    clock = f"{when:%H%M%S}.{when.microsecond // 10000:02d}"

    def degrees_minutes(value: float, width: int) -> str:
        whole = int(abs(value))
        return f"{whole:0{width}d}{(abs(value) - whole) * 60:07.4f}"

    lat, lon = degrees_minutes(fix.latitude_deg, 2), degrees_minutes(fix.longitude_deg, 3)
    gga = pynmea2.GGA("GP", "GGA", (clock, lat, "N", lon, "E", "4", "12", "0.6", f"{fix.altitude_m:.1f}", "M",
                                    "0.0", "M", "", ""))
    rmc = pynmea2.RMC("GP", "RMC", (clock, "A", lat, "N", lon, "E", f"{SPEED_MPS * 3600 / 1852:.2f}", "90.0",
                                    f"{when:%d%m%y}", "", "", "D"))
    return [gnss_pb2.NmeaChunk(data=f"{sentence}\r\n".encode(), port="test") for sentence in (gga, rmc)]


@pytest.fixture(scope="module")
def fixes_recording(tmp_path_factory):
    """A car driving east at 10 m/s: fixes at 10 Hz reaching the recorder 30 ms after they were sent, both as the
    simulator's gnss/fix and as the receiver's NMEA (gnss/nmea), whichever geolocation reads under replay."""
    path = tmp_path_factory.mktemp("wall") / "fixes.mcap"
    recorder = McapRecorder(path, metadata=config_metadata({"ego/geolocation": GeolocationConfig().model_dump_json()}))
    for index in range(FIXES):
        time_s = START_S + index * FIX_PERIOD_S
        fix = fix_at(time_s)
        recorder.write("coopdrive/ego/gnss/fix", fix, log_time_ns=round((time_s + ARRIVAL_DELAY_S) * NANOSECONDS))
        for position, chunk in enumerate(nmea_of(fix), start=1):
            arrival_s = time_s + ARRIVAL_DELAY_S + position * 0.001
            chunk.header.sent_time_s = chunk.header.sample_time_s = arrival_s
            chunk.header.vehicle_id, chunk.header.sender, chunk.header.sequence = "ego", "geolocation", index + 1
            recorder.write("coopdrive/ego/gnss/nmea", chunk, log_time_ns=round(arrival_s * NANOSECONDS))
    recorder.close()
    return path


def test_a_recording_without_a_clock_replays_its_inputs_with_the_triggers_at_their_periods(fixes_recording):
    result = replay_service(fixes_recording, "geolocation")
    assert result.mode == "wall" and result.steps >= FIXES  # fixes, or their NMEA, or both
    states = [m for topic, m in result.outputs if topic == "coopdrive/ego/ego/state"]
    times = [state.header.sample_time_s for state in states]
    assert times[0] == pytest.approx(START_S + ARRIVAL_DELAY_S)
    assert all(b - a == pytest.approx(0.02, abs=1e-6) for a, b in zip(times, times[1:]))
    assert len(states) == pytest.approx((FIXES - 1) * FIX_PERIOD_S / 0.02, abs=2)
    assert states[-1].speed_mps == pytest.approx(SPEED_MPS, abs=0.3)


def test_a_replayed_replay_reproduces_every_field_and_a_changed_setting_shows_which_moved(fixes_recording, tmp_path):
    first = tmp_path / "first.mcap"
    assert coopdrive("replay", str(fixes_recording), "--service", "geolocation", "--out", str(first)).returncode == 0
    assert any(m.topic == "coopdrive/ego/gnss/fix" for m in read_messages(first)), "--out keeps the inputs"
    again = coopdrive("replay", str(first), "--service", "geolocation", "--json")
    assert again.returncode == 0, again.stderr
    state = next(t for t in json.loads(again.stdout)["topics"] if t["topic"] == "ego/ego/state")
    assert state["paired"] == state["recorded"] == state["replayed"] > 0
    assert state["moved"] == {} and "x_m" in state["unchanged"]

    changed = coopdrive("replay", str(first), "--service", "geolocation", "--set", "geolocator.jerk_std_mps3=20",
                        "--set", "geolocator.gnss_reset_after_s=1", "--report", str(tmp_path / "report"))
    assert changed.returncode == 0, changed.stderr
    assert "changed: geolocator.jerk_std_mps3=20, geolocator.gnss_reset_after_s=1" in changed.stdout
    assert "    x_m " in changed.stdout and "max |diff|" in changed.stdout
    assert (tmp_path / "report" / "ego_ego_state.png").stat().st_size > 10_000
    assert json.loads((tmp_path / "report" / "differences.json").read_text())["mode"] == "wall"


def test_replaying_a_recording_without_the_service_s_inputs_exits_non_zero_naming_the_missing_topics(tmp_path):
    path = tmp_path / "radio_only.mcap"
    recorder = McapRecorder(path, metadata=config_metadata({"ego/geolocation": GeolocationConfig().model_dump_json()}))
    packet = v2x_pb2.GnPacket(payload=b"\x11\x00")
    packet.header.sent_time_s = START_S
    recorder.write("coopdrive/ego/v2x/rx", packet)
    recorder.close()
    result = coopdrive("replay", str(path), "--service", "geolocation")
    assert result.returncode == 2
    assert "holds no input of geolocation on vehicle ego: missing topics " in result.stderr
    assert "ego/gnss/" in result.stderr and "the recording has ego/v2x/rx" in result.stderr


def test_inputs_are_handled_in_arrival_order_and_a_trigger_fires_at_each_period_between_them():
    ctx = ReplayContext(vehicle_id="ego", service_name="geolocation")
    handled, ticks = [], []
    ctx.subscribe("gnss/fix", lambda envelope: handled.append((ctx.now_s(), envelope.message.header.sequence)))
    ctx.every(0.25, ticks.append)
    inputs = []
    for sequence, (sent_s, arrival_s) in enumerate([(10.0, 10.2), (10.1, 10.05), (10.3, 11.0)], start=1):
        fix = fix_at(sent_s)
        fix.header.sequence = sequence
        inputs.append(RecordedMessage("coopdrive/ego/gnss/fix", round(arrival_s * NANOSECONDS), fix))
    inputs.sort(key=lambda item: item.log_time_ns)  # as read_messages gives them
    assert run_wall_clock(ctx, inputs, [], KeyLayout()) == 3
    assert handled == [(pytest.approx(10.05), 2), (pytest.approx(10.2), 1), (pytest.approx(11.0), 3)]
    assert ticks == pytest.approx([10.05, 10.3, 10.55, 10.8])
