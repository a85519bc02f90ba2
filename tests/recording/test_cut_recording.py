"""A recording cut while it was written (its recorder killed, the power gone) is read up to its last whole chunk;
a file that is no recording at all is one clear error naming it."""

import json
import shutil

import pytest

from coopdrive.recording.reader import RecordingError, read_messages, read_metadata, recorded_topics
from coopdrive.recording.writer import McapRecorder
from coopdrive.v1 import ego_pb2

TOPIC = "coopdrive/ego/ego/state"
CHUNK_BYTES = 16 * 1024
MESSAGES = 3000
CUT_WARNING = "cut short while it was written"


def state(k: int) -> ego_pb2.EgoState:
    message = ego_pb2.EgoState(x_m=float(k), speed_mps=20.0)
    message.header.sample_time_s = message.header.sent_time_s = 0.01 * k
    return message


@pytest.fixture
def cut_recording(tmp_path):
    """The file as a kill leaves it: what the recorder had handed to the system, without its end."""
    recorder = McapRecorder(tmp_path / "live.mcap", visuals=False, chunk_bytes=CHUNK_BYTES)
    recorder.learn_config("ego/geolocation", json.dumps({"gnss_port": "/dev/ttyACM0"}))
    for k in range(MESSAGES):
        recorder.write(TOPIC, state(k))
    cut = tmp_path / "cut.mcap"
    shutil.copy(recorder.path, cut)
    recorder.close()
    return cut


def test_a_cut_recording_gives_every_message_before_its_last_whole_chunk_and_loses_at_most_one_chunk(
        cut_recording, caplog):
    with caplog.at_level("WARNING", logger="coopdrive.recording.reader"):
        read = list(read_messages(cut_recording))
    assert 0 < len(read) < MESSAGES
    assert [m.message for m in read] == [state(k) for k in range(len(read))]
    lost_bytes = sum(len(state(k).SerializeToString()) for k in range(len(read), MESSAGES))
    assert lost_bytes <= CHUNK_BYTES
    assert sum(CUT_WARNING in record.getMessage() and str(cut_recording) in record.getMessage()
               for record in caplog.records) == 1


def test_a_cut_recording_keeps_the_configs_its_recorder_learned_before_the_cut(cut_recording):
    config = read_metadata(cut_recording)["coopdrive.config"]["ego/geolocation"]
    assert json.loads(config) == {"gnss_port": "/dev/ttyACM0"}
    assert recorded_topics(cut_recording) == [TOPIC]


def test_configs_written_one_by_one_are_read_back_together(tmp_path):
    recorder = McapRecorder(tmp_path / "run.mcap", visuals=False)
    recorder.learn_config("ego/geolocation", "{}")
    recorder.learn_config("ego/scene", "{}")
    recorder.learn_config("ego/geolocation", '{"changed": true}')
    recorder.close()
    assert read_metadata(recorder.path)["coopdrive.config"] == {"ego/geolocation": '{"changed": true}',
                                                                "ego/scene": "{}"}


def test_a_whole_recording_is_read_through_its_index_without_a_warning(tmp_path, caplog):
    recorder = McapRecorder(tmp_path / "run.mcap", visuals=False, chunk_bytes=CHUNK_BYTES)
    for k in range(MESSAGES):
        recorder.write(TOPIC, state(k))
    recorder.close()
    with caplog.at_level("WARNING", logger="coopdrive.recording.reader"):
        assert len(list(read_messages(recorder.path))) == MESSAGES
    assert not caplog.records


@pytest.mark.parametrize("content, reason", [(b"not a recording\n", "no MCAP magic at its start"),
                                             (None, "No such file or directory")])
def test_a_file_that_is_no_recording_is_one_error_naming_it(tmp_path, content, reason):
    path = tmp_path / "drive.mcap"
    if content is not None:
        path.write_bytes(content)
    with pytest.raises(RecordingError, match=f"{path}: not a readable MCAP recording .*{reason}"):
        list(read_messages(path))


@pytest.mark.parametrize("from_s, to_s, named", [(-1.0, None, "--from -1"), (5.0, 3.0, "--to 3")])
def test_a_replay_window_that_is_no_window_is_one_error_naming_the_option(from_s, to_s, named):
    from coopdrive.recording.replay import ReplayError, TimeWindow

    with pytest.raises(ReplayError, match=named):
        TimeWindow(from_s, to_s)


def test_a_window_reads_only_the_messages_logged_inside_it_whole_or_cut(tmp_path, cut_recording):
    recorder = McapRecorder(tmp_path / "run.mcap", visuals=False, chunk_bytes=CHUNK_BYTES)
    for k in range(MESSAGES):
        recorder.write(TOPIC, state(k))
    recorder.close()
    for path in (recorder.path, cut_recording):
        window = [m.message.x_m for m in read_messages(path, start_ns=int(1e9), end_ns=int(2e9))]
        assert window == [float(k) for k in range(100, 200)]


def test_a_recorder_whose_disk_fills_stops_in_one_line_and_leaves_what_it_wrote_readable(tmp_path):
    """The recorder's file may grow to FILE_LIMIT_BYTES only (a write past it fails, as on a full disk): it stops
    by itself with exit code 1, says so once (not once per message), and the file reads back as a cut one."""
    import resource
    import signal
    import subprocess
    import sys
    import time

    from coopdrive.bus import Bus, BusConfig
    from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
    from tests.recording.live_bus import wait_recording

    file_limit_bytes = 512 * 1024

    def as_on_a_full_disk():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # the write fails (EFBIG) instead of killing the process
        resource.setrlimit(resource.RLIMIT_FSIZE, (file_limit_bytes, file_limit_bytes))

    endpoint = loopback_endpoint(free_tcp_port())
    hub = Bus(BusConfig(listen=[endpoint]))
    path = tmp_path / "drive.mcap"
    recorder = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "record", str(path), "--connect", endpoint,
                                 "--duration", "120"], preexec_fn=as_on_a_full_disk, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
    try:
        wait_recording(hub)
        sent = 0
        while recorder.poll() is None and sent < 200_000:
            hub.publish("ego", "ego/state", state(sent))
            sent += 1
            if sent % 500 == 0:
                time.sleep(0.01)
        _, err = recorder.communicate(timeout=60)
    finally:
        if recorder.poll() is None:
            recorder.kill()
        hub.close()
    assert recorder.returncode == 1, err
    assert err.count("recording stopped") == 1 and f"coopdrive: record: {path}: stopped early" in err, err
    read = [m.message.x_m for m in read_messages(path)]
    assert read and read == sorted(read) and path.stat().st_size <= file_limit_bytes
