"""A recorded run opens in Foxglove: `coopdrive run merge --stacks 2 --record` carries Foxglove's own channels."""

import subprocess
import sys

import pytest

from coopdrive.recording.reader import read_messages
from coopdrive.v1 import ego_pb2, scene_pb2
from tests.visual.foxglove_mcap import foxglove_channels

pytestmark = pytest.mark.whole_run

STACKS = ("a1", "a2")


@pytest.fixture(scope="module")
def merge_recording(tmp_path_factory):
    path = tmp_path_factory.mktemp("merge") / "m.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "merge", "--stacks", "2", "--duration",
                             "6", "--record", str(path)], capture_output=True, text=True, timeout=300)
    assert path.exists(), result.stdout + result.stderr
    return path


def stack_messages(path, vehicle, topic, cls):
    return [m.message for m in read_messages(path)
            if m.topic == f"coopdrive/{vehicle}/{topic}" and isinstance(m.message, cls)]


def test_the_recording_holds_location_fix_frame_transforms_and_scene_update_channels_in_foxglove_s_schemas(
        merge_recording):
    channels = foxglove_channels(merge_recording)
    for vehicle in STACKS:
        for topic in ("ego", "gnss", "v2x_stations", "scene"):
            assert channels[f"foxglove/{vehicle}/{topic}"], f"no foxglove/{vehicle}/{topic}"
    children = {t.child_frame_id for message in channels["foxglove/transforms"] for t in message.transforms}
    assert children == set(STACKS)
    assert channels["foxglove/map"] and channels["foxglove/ground_truth"]
    assert {"truth/a1", "truth/traffic"} <= {e.id for e in channels["foxglove/ground_truth"][-1].entities}


def test_one_location_fix_per_ego_estimate_that_has_a_position(merge_recording):
    channels = foxglove_channels(merge_recording)
    for vehicle in STACKS:
        estimates = [e for e in stack_messages(merge_recording, vehicle, "ego/state", ego_pb2.EgoState)
                     if e.latitude_deg or e.longitude_deg]
        fixes = channels[f"foxglove/{vehicle}/ego"]
        assert [(f.latitude, f.longitude) for f in fixes] == [(e.latitude_deg, e.longitude_deg) for e in estimates]


def test_the_scene_updates_hold_the_scene_s_objects_message_by_message(merge_recording):
    channels = foxglove_channels(merge_recording)
    for vehicle in STACKS:
        scenes = stack_messages(merge_recording, vehicle, "scene", scene_pb2.Scene)
        updates = channels[f"foxglove/{vehicle}/scene"]
        assert len(updates) == len(scenes) > 0
        for scene, update in zip(scenes, updates):
            drawn = sorted(e.id for e in update.entities if "/object/" in e.id)
            assert drawn == sorted(f"{vehicle}/object/{o.object_id}" for o in scene.objects)
            if scene.has_mio:
                [mio] = [e for e in update.entities if e.id == f"{vehicle}/object/{scene.mio_id}"]
                assert mio.texts[0].text.endswith("MIO")
        assert any(scene.objects for scene in scenes)


def test_export_adds_the_foxglove_channels_to_a_recording_made_without_them(merge_recording, tmp_path):
    from coopdrive.recording.reader import read_metadata
    from coopdrive.recording.writer import McapRecorder

    bare = tmp_path / "old.mcap"
    recorder = McapRecorder(bare, read_metadata(merge_recording), visuals=False)
    for recorded in read_messages(merge_recording):
        recorder.write(recorded.topic, recorded.message, log_time_ns=recorded.log_time_ns)
    recorder.close()
    assert not foxglove_channels(bare)
    out = tmp_path / "with_foxglove.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "export", str(bare), "--foxglove", str(out)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert {topic: len(messages) for topic, messages in foxglove_channels(out).items()} == \
        {topic: len(messages) for topic, messages in foxglove_channels(merge_recording).items()}
    assert read_metadata(out) == read_metadata(merge_recording)
    assert len(list(read_messages(out))) == len(list(read_messages(merge_recording)))


def test_export_names_a_file_that_is_not_a_recording_in_one_line(tmp_path):
    bad = tmp_path / "bad.mcap"
    bad.write_text("not mcap")
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "export", str(bad), "--foxglove",
                             str(tmp_path / "out.mcap")], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "bad.mcap" in result.stderr


def test_every_topic_the_layout_names_is_in_the_recording_but_the_signals_where_no_rsu_sends_a_map(merge_recording):
    """merge has no traffic light: its vehicles hear no MAPEM, so there is nothing to draw on foxglove/<v>/signals
    (the signals run's recording holds it: tests/sim/test_signals_run.py)."""
    from mcap.reader import make_reader

    from coopdrive.visual.channels import vehicle_topic
    from coopdrive.visual.layout import drive_layout, layout_topics

    with open(merge_recording, "rb") as stream:
        recorded = {channel.topic for channel in make_reader(stream).get_summary().channels.values()}
    for vehicle in STACKS:
        named = layout_topics(drive_layout(vehicle).to_json())
        assert named - recorded == {vehicle_topic(vehicle, "signals")}, \
            f"{vehicle}: the layout names topics the recording lacks"


def test_an_imported_nmea_log_opens_in_foxglove_with_its_fixes_on_the_map(tmp_path):
    from coopdrive.gnss.nmea_decoder import with_checksum

    log = tmp_path / "drive.nmea"
    lines = []
    for second in range(5):
        latitude = f"5128.{548 + second}"
        lines += [with_checksum(f"GPGGA,12000{second}.00,{latitude},N,00537.482,E,4,12,0.8,20.0,M,47.0,M,,"),
                  with_checksum(f"GPRMC,12000{second}.00,A,{latitude},N,00537.482,E,10.0,90.0,250926,,,D"),
                  with_checksum(f"GPGST,12000{second}.00,0.5,0.02,0.02,0,0.02,0.03,0.05")]
    log.write_text("\r\n".join(lines) + "\r\n")
    out = tmp_path / "drive.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "import", "--nmea", str(log), "--out", str(out)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    fixes = foxglove_channels(out)["foxglove/ego/gnss"]
    assert len(fixes) >= 4  # the last epoch may wait for a next one that never comes
    assert fixes[0].latitude == pytest.approx(51 + 28.548 / 60)
