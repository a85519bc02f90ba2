"""The ACT_ frames a real follow run sent on can/command, logged in candump format, replayed through
python-can's player (LogReader + MessageSync) and decoded with the DBC, give back the commands sent live."""

from __future__ import annotations

import threading

import can

from coopdrive.can.candump import CandumpLogger
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.wire import to_python_can
from coopdrive.launch.run import RunOptions, run_scenario

RUN_DURATION_S = 4.0
# Replay as fast as possible: the timing of the replay is not what is checked here.
REPLAY_TIME_SCALING = 0.0


def record_run(path) -> list[can.Message]:
    recorded: list[can.Message] = []
    lock = threading.Lock()

    def observe(key: str, message) -> None:
        if key.endswith("ego/can/command"):
            with lock:
                recorded.append(to_python_can(message))

    result = run_scenario(RunOptions(duration_s=RUN_DURATION_S, observer=observe))
    assert result.metrics["collisions"] == 0
    with lock:
        frames = sorted(recorded, key=lambda m: m.timestamp)
    with CandumpLogger(path) as logger:
        logger.write_all(frames)
    return frames


def test_the_command_frames_of_a_run_replayed_from_a_candump_log_decode_to_the_recorded_commands(tmp_path):
    path = tmp_path / "follow-can.log"
    recorded = record_run(path)
    assert recorded, "the run sent no ACT_ frames on can/command"
    replayed = list(can.MessageSync(can.LogReader(str(path)), timestamps=True, gap=0.0, skip=0.0))
    assert len(replayed) == len(recorded)
    live, logged = VehicleCanCodec(), VehicleCanCodec()
    expected = [live.decode_command(msg) for msg in recorded]
    assert [logged.decode_command(msg) for msg in replayed] == expected
    assert any(command.throttle_ratio > 0 or command.brake_ratio > 0 for command in expected)
