"""`coopdrive run FILE.yaml --stacks N`: several whole stacks, each under its own vehicle id, in one scenario."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from coopdrive.recording.reader import read_messages

pytestmark = pytest.mark.whole_run

EXAMPLE = Path(__file__).parents[2] / "services" / "sim" / "examples" / "string_stability.yaml"


def coopdrive(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True,
                          timeout=timeout)


@pytest.fixture(scope="module")
def two_stacks(tmp_path_factory):
    recording = tmp_path_factory.mktemp("scenario") / "run.mcap"
    # Exact answers (one decoded fix per NMEA epoch written, reception above 0.9): the ideal world.
    result = coopdrive("run", str(EXAMPLE), "--stacks", "2", "--duration", "8", "--world", "ideal", "--json",
                       "--record", str(recording))
    assert result.returncode == 0, result.stdout + result.stderr
    return json.loads(result.stdout), recording


def test_two_stacks_follow_the_scripted_leader_without_collision(two_stacks):
    summary, _ = two_stacks
    assert summary["scenario"] == "string_stability"
    assert summary["success"] is True and summary["collisions"] == 0
    assert summary["min_gap_m"] > 6.0


def test_each_stack_runs_under_its_own_vehicle_id_and_hears_the_other_over_the_radio(two_stacks):
    _, recording = two_stacks
    status = {}
    senders = set()
    for item in read_messages(recording):
        header = item.message.header if item.message.DESCRIPTOR.fields_by_name.get("header") else None
        if header is not None and header.vehicle_id in ("ego", "f2"):
            senders.add((header.vehicle_id, header.sender))
        if item.message.DESCRIPTOR.name == "V2xStatus":
            status[item.message.header.vehicle_id] = item.message
    for vehicle in ("ego", "f2"):
        for service in ("geolocation", "scene", "planner", "control", "actuation", "v2x"):
            assert (vehicle, service) in senders
    heard = {vehicle: {s.station_id: s for s in message.stations} for vehicle, message in status.items()}
    assert heard["ego"][103].reception_ratio > 0.9 and heard["f2"][102].reception_ratio > 0.9
    assert not status["ego"].rejected_by_reason and not status["f2"].rejected_by_reason


def test_a_malformed_scenario_file_is_one_line_naming_the_key_and_nothing_starts(tmp_path):
    broken = tmp_path / "broken.yaml"
    broken.write_text(EXAMPLE.read_text().replace("speed_mps: 11.1, platoon: 2", "speed_mps: fast, platoon: 2", 1))
    result = coopdrive("run", str(broken), timeout=60)
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "vehicles.1.speed_mps" in result.stderr
    assert result.stdout == ""


def test_asking_for_more_stacks_than_the_scenario_has_is_refused():
    result = coopdrive("run", str(EXAMPLE), "--stacks", "9", timeout=60)
    assert result.returncode == 2 and "--stacks 9" in result.stderr


def test_each_stack_reads_its_gnss_as_nmea_from_its_own_serial_line(two_stacks):
    _, recording = two_stacks
    counts = {}
    for item in read_messages(recording):
        if item.topic.endswith(("gnss/serial_mark", "ego/gnss", "gnss/fix")):
            counts[item.topic] = counts.get(item.topic, 0) + 1
    for vehicle in ("ego", "f2"):
        marks = counts.get(f"coopdrive/{vehicle}/gnss/serial_mark", 0)
        assert marks > 50, "the simulator wrote no NMEA epochs"
        assert counts.get(f"coopdrive/{vehicle}/ego/gnss", 0) == marks, "an epoch on the line was not decoded"
        assert f"coopdrive/{vehicle}/gnss/fix" not in counts


def test_every_byte_geolocation_read_from_its_gnss_line_is_on_gnss_nmea_up_to_a_serial_mark(two_stacks):
    _, recording = two_stacks
    marks, chunks = {}, {}
    for item in read_messages(recording):
        vehicle = item.topic.split("/")[1]
        if item.topic.endswith("gnss/serial_mark"):
            marks.setdefault(vehicle, []).append(item.message.written)
        elif item.topic.endswith("gnss/nmea"):
            chunks.setdefault(vehicle, []).append(item.message)
    for vehicle in ("ego", "f2"):
        data = b"".join(chunk.data for chunk in chunks[vehicle])
        # Reads stop exactly at marks; the run may end before the last mark is read.
        assert len(data) in marks[vehicle][-2:]
        assert data.startswith(b"$") and all(chunk.port.endswith(f"{vehicle}-gnss0") for chunk in chunks[vehicle])


@pytest.mark.parametrize("service", ["geolocation", "scene"])
def test_a_stack_service_replayed_over_the_run_reproduces_its_outputs_exactly(two_stacks, service):
    """geolocation's input is the bytes its own driver side put on gnss/nmea (it read them from a pty); scene's
    the car's CAN bus (can/vehicle), the ego state and V2X."""
    _, recording = two_stacks
    result = coopdrive("replay", str(recording), "--service", service, "--vehicle", "f2")
    assert "identical to the recorded outputs" in result.stdout, result.stdout[-2000:]


def test_a_replay_reads_only_the_channels_that_can_concern_its_service(two_stacks, monkeypatch):
    """ego's own channels that f2's scene does not subscribe to are neither decoded nor put in time order, and the
    replay still reproduces every output."""
    from coopdrive.bus import KeyLayout
    from coopdrive.recording import replay
    from coopdrive.recording.reader import recorded_topics

    _, recording = two_stacks
    asked, read_all = [], replay.read_messages

    def read_and_note(path, topics=None, *window_ns):
        asked.append(topics)
        return read_all(path, topics, *window_ns)

    monkeypatch.setattr(replay, "read_messages", read_and_note)
    result = replay.replay_service(recording, "scene", "f2")
    assert result.outputs and not result.mismatches()
    layout = KeyLayout()
    left_out = {layout.split(key) for key in set(recorded_topics(recording)) - set(asked[0])
                if key.startswith(layout.root)}
    assert ("ego", "scene") in left_out and not any(vehicle == "f2" for vehicle, _ in left_out)


def test_a_window_of_the_run_replays_only_its_steps_and_compares_only_its_outputs(two_stacks):
    """The service starts at --from with none of its recorded state: differences are reported, not a failure."""
    _, recording = two_stacks
    result = coopdrive("replay", str(recording), "--service", "scene", "--vehicle", "f2", "--from", "4", "--to", "7",
                       "--json")
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert report["window_s"] == [4.0, 7.0] and report["mode"] == "lockstep"
    assert 145 <= report["steps"] <= 151  # 3 s of 20 ms steps
    scene = next(topic for topic in report["topics"] if topic["topic"] == "f2/scene")
    assert scene["paired"] == scene["recorded"] > 0
    assert any("started at 4 s" in note for note in report["notes"])
