"""The closed loop of the foundation: `coopdrive run follow` as a user runs it."""

import json
import math
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import can
import cantools
import pytest
from mcap.reader import make_reader

from coopdrive.can.frames import DBC_FILE
from coopdrive.launch.summary import WALL_CLOCK_KEYS
from coopdrive.recording.reader import read_messages
from coopdrive.recording.replay import replay_service
from coopdrive.recording.spool_merge import SPOOL_SUFFIX

pytestmark = pytest.mark.whole_run

# A run ends within this long of SIGTERM, its recording complete (measured: 0.62-0.72 s).
SIGTERM_STOP_S = 3.0
# A few seconds of a realtime follow run's messages (about 4 s on a quiet 2-core machine).
SPOOLED_BEFORE_THE_SIGNAL_BYTES = 1_000_000

STANDSTILL_M = 6.0
DURATION = "18"
# Lockstep steps in flight for the second run, one fewer than the simulator's default.
FEWER_STEPS_IN_FLIGHT = 2


def run_follow(*extra: str) -> dict:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--seed", "1", "--json",
                             "--duration", DURATION, *extra], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def recorded_run(tmp_path_factory):
    recording = tmp_path_factory.mktemp("follow") / "follow.mcap"
    return run_follow("--record", str(recording)), recording


def test_the_ego_follows_without_collision_and_keeps_the_standstill_distance(recorded_run):
    summary, _ = recorded_run
    assert summary["success"] is True
    assert summary["collisions"] == 0
    assert summary["min_gap_m"] > STANDSTILL_M
    assert summary["sim_time_s"] == pytest.approx(float(DURATION))
    for key in ("scenario", "seed", "success", "sim_time_s", "wall_time_s", "collisions", "min_gap_m"):
        assert key in summary


def test_the_summary_says_lockstep_never_went_on_without_a_promised_message(recorded_run):
    summary, _ = recorded_run
    assert summary["lockstep_messages_given_up"] == 0


def test_the_same_seed_gives_identical_metrics_with_one_process_per_service_and_fewer_lockstep_steps_in_flight(
        recorded_run):
    """One run changes both, the layout and the steps in flight (the simulator's default is 3), so that the suite
    pays for one more run, not two: either change alone would show here as a difference."""
    first, _ = recorded_run
    second = run_follow("--processes", "service", "--set", f"sim.feedback_delay_steps={FEWER_STEPS_IN_FLIGHT}")
    assert {k: v for k, v in first.items() if k not in WALL_CLOCK_KEYS} == \
        {k: v for k, v in second.items() if k not in WALL_CLOCK_KEYS}


def test_the_recording_holds_every_service_with_its_schema(recorded_run):
    _, recording = recorded_run
    senders = Counter(message.message.header.sender for message in read_messages(recording))
    for service in ("sim", "geolocation", "scene", "planner", "control", "actuation"):
        assert senders[service] > 0, f"nothing from {service} in the recording"


def test_the_recording_holds_what_the_stack_published_in_the_last_step_too(recorded_run):
    summary, recording = recorded_run
    commands_s = [m.message.header.sample_time_s for m in read_messages(recording)
                  if m.topic == "coopdrive/ego/can/command"]
    assert max(commands_s) == pytest.approx(summary["sim_time_s"])


def test_the_ego_s_can_bus_in_the_recording_decodes_with_the_dbc_to_the_true_speed_and_radar_range(recorded_run):
    _, recording = recorded_run
    dbc = cantools.database.load_file(str(Path(__file__).parents[2] / "coopdrive" / "can" / DBC_FILE))
    truth_by_time, decoded = {}, []
    for recorded in read_messages(recording):
        if recorded.topic.endswith("world/ground_truth"):
            vehicles = {v.vehicle_id: v for v in recorded.message.vehicles}
            truth_by_time[round(recorded.message.header.sample_time_s, 2)] = vehicles
        elif recorded.topic.endswith("ego/can/vehicle"):
            for frame in recorded.message.frames:
                decoded.append((frame.timestamp_s, dbc.get_message_by_frame_id(frame.arbitration_id).name,
                                dbc.decode_message(frame.arbitration_id, frame.data)))
    speeds = [(t, s["WheelSpeedRearLeft"]) for t, name, s in decoded if name == "VEH_WheelSpeeds"]
    objects = [(t, s["DistLong"]) for t, name, s in decoded if name == "RDR_Object"]
    assert len(speeds) > 100 and len(objects) > 100
    for time_s, speed_mps in speeds:
        if round(time_s, 2) in truth_by_time:
            assert speed_mps == pytest.approx(truth_by_time[round(time_s, 2)]["ego"].speed_mps, abs=0.2)
    # The real world's radar misses some scans and reports false tracks: most scans hold an object at the leader's
    # rear (between its rear axle and a car length behind it, within the radar's noise and bias), not every one.
    by_scan: dict[float, list[float]] = {}
    for time_s, dist_m in objects:
        if round(time_s, 2) in truth_by_time:
            by_scan.setdefault(round(time_s, 2), []).append(dist_m)
    at_leader = 0
    for time_s, distances_m in by_scan.items():
        ego, leader = truth_by_time[time_s]["ego"], truth_by_time[time_s]["leader"]
        apart_m = math.hypot(leader.x_m - ego.x_m, leader.y_m - ego.y_m)
        at_leader += any(apart_m - leader.length_m - 1.0 < d < apart_m + 1.0 for d in distances_m)
    assert at_leader >= 0.9 * len(by_scan) >= 20


def test_coopdrive_candump_writes_the_ego_s_bus_as_a_candump_log_that_python_can_reads_back(recorded_run, tmp_path):
    _, recording = recorded_run
    log = tmp_path / "ego-can.log"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "candump", str(recording), "--vehicle", "ego",
                             "--out", str(log)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    frames = list(can.LogReader(str(log)))
    assert result.stdout.startswith(f"{len(frames)} frames of ego")
    dbc = cantools.database.load_file(str(Path(__file__).parents[2] / "coopdrive" / "can" / DBC_FILE))
    names = Counter(dbc.get_message_by_frame_id(frame.arbitration_id).name for frame in frames)
    assert {"ACT_LongitudinalCommand", "VEH_WheelSpeeds", "RDR_ObjectListStatus"} <= set(names)
    assert [f.timestamp for f in frames] == sorted(f.timestamp for f in frames)


def test_coopdrive_candump_of_a_vehicle_without_frames_names_the_vehicles_that_have_them(recorded_run, tmp_path):
    _, recording = recorded_run
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "candump", str(recording), "--vehicle", "nobody",
                             "--out", str(tmp_path / "x.log")], capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert "no CAN frames of vehicle 'nobody' (vehicles with frames: ego)" in result.stderr


def channels_of(path: Path) -> dict[str, list[tuple[int, bytes]]]:
    """Every channel of an MCAP file, Foxglove's included: each message's log time and bytes, in log-time order."""
    channels: dict[str, list[tuple[int, bytes]]] = {}
    with path.open("rb") as file:
        for _, channel, message in make_reader(file).iter_messages(log_time_order=True):
            channels.setdefault(channel.topic, []).append((message.log_time, message.data))
    return channels


@pytest.fixture(scope="module")
def recorded_channels(recorded_run):
    return channels_of(recorded_run[1])


@pytest.mark.parametrize("service", ["geolocation", "v2x", "scene", "planner", "control", "actuation"])
def test_replaying_a_service_writes_every_channel_of_the_recording_it_holds_message_for_message(
        recorded_run, recorded_channels, service, tmp_path):
    """The replayed outputs, the inputs fed and what Foxglove draws from them: a replay opened in Foxglove shows
    what the car saw. Diagnostics carry the replaying machine's timings, not the recorded ones."""
    _, recording = recorded_run
    result = replay_service(recording, service, out=tmp_path / f"{service}.mcap")
    assert result.recorded_outputs, "the recording holds no outputs of the service"
    assert result.mismatches() == []
    replayed = {topic: messages for topic, messages in channels_of(tmp_path / f"{service}.mcap").items()
                if "/diagnostics/" not in topic}
    assert {topic for topic, _ in result.outputs if "/diagnostics/" not in topic} <= set(replayed)
    assert {"foxglove/ego/scene", "foxglove/ego/ego", "foxglove/map", "foxglove/transforms"} <= set(replayed)
    differing = {topic: sum(a != b for a, b in zip(messages, recorded_channels.get(topic, [])))
                 for topic, messages in replayed.items() if messages != recorded_channels.get(topic)}
    assert differing == {}, f"channels whose messages differ from the recording's (how many): {differing}"


def test_the_replay_command_reports_identical_outputs(recorded_run, tmp_path):
    _, recording = recorded_run
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "replay", str(recording), "--service", "control",
                             "--out", str(tmp_path / "control.mcap")], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "identical to the recorded outputs" in result.stdout


def spooled_bytes(folder: Path) -> int:
    return sum(path.stat().st_size for path in folder.glob(f"coopdrive-run-*/spools/*{SPOOL_SUFFIX}"))


def recorded_bytes(recording: Path) -> int:
    return recording.stat().st_size if recording.exists() else 0


def test_sigterm_ends_a_realtime_run_without_hanging_and_leaves_a_complete_recording(tmp_path):
    recording = tmp_path / "stopped.mcap"
    # The run's processes spool what they publish in its folder under TMPDIR; stopped once they have spooled some.
    process = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--realtime",
                                "--record", str(recording)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env={**os.environ, "TMPDIR": str(tmp_path)})
    deadline = time.monotonic() + 60
    # The spools are merged into the recording as the run goes, so that a stop merges only its last moments.
    while ((spooled_bytes(tmp_path) < SPOOLED_BEFORE_THE_SIGNAL_BYTES or recorded_bytes(recording) == 0)
           and time.monotonic() < deadline):
        time.sleep(0.5)
    assert recorded_bytes(recording) > 0
    stopped_at = time.monotonic()
    process.send_signal(signal.SIGTERM)
    process.wait(timeout=30)
    assert time.monotonic() - stopped_at < SIGTERM_STOP_S
    topics = Counter(message.topic for message in read_messages(recording))
    assert topics["coopdrive/ego/actuation/command"] > 0
    assert topics["coopdrive/world/clock"] > 0
