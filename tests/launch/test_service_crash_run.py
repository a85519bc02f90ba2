"""Issue 26: a service_crash that happens. platoon40 with one stack whose control process is killed at 4 s and
restarted at 7 s: actuation's watchdog starts a safe stop within its command timeout, control publishes again
after the restart, and the same seed gives the same metrics (the simulator holds its clock at both steps)."""

import json
import subprocess
import sys

import pytest

from coopdrive.can.codec import VehicleCanCodec
from coopdrive.launch.summary import WALL_CLOCK_KEYS
from coopdrive.recording.reader import read_messages, read_metadata
from coopdrive.v1 import actuation_pb2

pytestmark = pytest.mark.whole_run

CRASH_AT_S = 4.0
RESTART_AT_S = 7.0
DURATION_S = 12.0
FAULT = f"{{type: service_crash, vehicle_id: p1, service: control, start_s: {CRASH_AT_S}, end_s: {RESTART_AT_S}}}"
RUN_TIMEOUT_S = 600
CONTROL_PERIOD_S = 0.02  # control runs at 50 Hz
# Metrics of the wall clock, the only ones two runs of one seed may differ in.


def crash_run(recording=None) -> dict:
    command = [sys.executable, "-m", "coopdrive.cli", "run", "platoon40", "--stacks", "1", "--seed", "3",
               "--duration", str(DURATION_S), "--fault", FAULT, "--json"]
    if recording is not None:
        command += ["--record", str(recording)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    recording = tmp_path_factory.mktemp("crash") / "run.mcap"
    summary = crash_run(recording)
    messages = [(r.topic, r.message) for r in read_messages(recording)]
    actuation_config = json.loads(read_metadata(recording)["coopdrive.config"]["p1/actuation"])
    return summary, messages, actuation_config


def sample_times_s(messages, topic_suffix: str) -> list[float]:
    return [m.header.sample_time_s for topic, m in messages if topic.endswith(topic_suffix)]


def test_the_crash_and_the_restart_are_carried_out_and_reported(recorded):
    summary, _, _ = recorded
    assert summary["service_crashes"] == 1 and summary["service_restarts"] == 1
    assert summary["participants_lost"] == 1
    # The fallback of the crashed car is the reaction under test, not a failure; a collision would fail it.
    assert summary["success"], summary["failure_reason"]
    assert summary["collisions"] == 0


def test_actuation_starts_a_safe_stop_within_its_watchdog_time_after_control_dies(recorded):
    summary, messages, actuation_config = recorded
    timeout_s = actuation_config["actuator"]["watchdog"]["command_timeout_s"]
    actuation_period_s = 1.0 / actuation_config["rate_hz"]
    codec = VehicleCanCodec()
    modes = [(m.header.sample_time_s, codec.decode_command_frame(m).driving_mode) for topic, m in messages
             if topic.endswith("p1/can/command")]
    assert any(mode == actuation_pb2.DRIVING_MODE_AUTONOMOUS for t, mode in modes if t < CRASH_AT_S)
    stop_s = min(t for t, mode in modes if t >= CRASH_AT_S and mode == actuation_pb2.DRIVING_MODE_SAFE_STOP)
    last_command_s = max(t for t in sample_times_s(messages, "p1/control/command") if t < CRASH_AT_S)
    assert stop_s - last_command_s <= timeout_s + actuation_period_s + 1e-6, (last_command_s, stop_s)
    assert summary["crash_to_safe_stop_s"] == pytest.approx(stop_s - CRASH_AT_S, abs=1e-6)
    statuses = [m for topic, m in messages if topic.endswith("p1/actuation/status") and m.header.sample_time_s > stop_s]
    assert statuses and all(s.mode == actuation_pb2.DRIVING_MODE_SAFE_STOP and s.hazard_lights for s in statuses[:5])


def test_the_restarted_control_service_publishes_again_from_its_restart_on(recorded):
    _, messages, _ = recorded
    commands_s = sample_times_s(messages, "p1/control/command")
    assert not [t for t in commands_s if CRASH_AT_S <= t < RESTART_AT_S]
    resumed = [t for t in commands_s if t >= RESTART_AT_S]
    assert resumed and resumed[0] == pytest.approx(RESTART_AT_S)
    assert len(resumed) > 0.8 * (DURATION_S - RESTART_AT_S) / CONTROL_PERIOD_S  # to the end of the run


def test_a_second_run_with_the_same_seed_gives_identical_metrics(recorded):
    first, _, _ = recorded
    second = crash_run()
    assert {k: v for k, v in second.items() if k not in WALL_CLOCK_KEYS} == \
        {k: v for k, v in first.items() if k not in WALL_CLOCK_KEYS}


def test_the_recording_holds_every_ground_truth_step_and_what_the_killed_service_sent_up_to_its_kill(recorded):
    """Each process spools what it publishes, so neither a killed process nor a loaded launcher costs the
    recording a message (a launcher subscribed to everything had lost ~10 s of every message under load)."""
    _, messages, _ = recorded
    truth_s = [m.header.sent_time_s for topic, m in messages if topic == "coopdrive/world/ground_truth"]
    period_s = truth_s[1] - truth_s[0]
    assert truth_s == pytest.approx([step * period_s for step in range(round(DURATION_S / period_s) + 1)])
    before_the_kill_s = [t for t in sample_times_s(messages, "p1/control/command") if t < CRASH_AT_S]
    assert max(before_the_kill_s) == pytest.approx(CRASH_AT_S - CONTROL_PERIOD_S)
