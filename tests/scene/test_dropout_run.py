"""Issue 7 in the simulator: a stack behind a scripted leader whose radar, LiDAR and camera drop out for 2 s
keeps the leader as its forward MIO on V2V alone, with lower confidence and the same id; when every source of
the leader stops, its position fades on the configured schedule and the object goes."""

import subprocess
import sys

import pytest

from coopdrive.recording.reader import read_messages
from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.v1 import header_pb2, scene_pb2
from tests.scenario_report import FASTEST_LAYOUT

pytestmark = pytest.mark.whole_run

DROPOUT_S = (6.0, 8.0)
ALL_STOP_S = 10.5
V2V = header_pb2.SENSOR_SOURCE_V2V
SCENARIO = """
name: sensor_dropout
description: A stack behind a scripted leader loses its ranging sensors for 2 s, then every source.
map: a270
seed: 3
# Exact answers (one MIO id through the dropout, nothing but the faults' own losses): the ideal world.
world: ideal
duration_s: 13
step_s: 0.02
vehicles:
  - {vehicle_id: leader, station_id: 101, role: scripted, lane: 0, station_m: 200, speed_mps: 15.0}
  - {vehicle_id: ego, station_id: 102, lane: 0, station_m: 172, speed_mps: 15.0}
faults:
""" + "".join(
    f"  - {{type: sensor_dropout, vehicle_id: ego, sensor: {sensor}, start_s: {DROPOUT_S[0]}, end_s: {DROPOUT_S[1]}}}\n"
    f"  - {{type: sensor_dropout, vehicle_id: ego, sensor: {sensor}, start_s: {ALL_STOP_S}}}\n"
    for sensor in ("radar", "lidar", "camera")) + (
    f"  - {{type: v2v_loss, vehicle_id: ego, loss_probability: 1.0, start_s: {ALL_STOP_S}}}\n")


@pytest.fixture(scope="module")
def scenes(tmp_path_factory) -> list[scene_pb2.Scene]:
    folder = tmp_path_factory.mktemp("dropout")
    (folder / "dropout.yaml").write_text(SCENARIO)
    recording = folder / "run.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(folder / "dropout.yaml"),
                             "--record", str(recording), *FASTEST_LAYOUT], capture_output=True, text=True,
                            timeout=600)
    assert result.returncode in (0, 1), result.stderr
    return [m.message for m in read_messages(recording)
            if isinstance(m.message, scene_pb2.Scene) and m.message.header.vehicle_id == "ego"]


def leader(scene: scene_pb2.Scene) -> scene_pb2.SceneObject | None:
    return next((o for o in scene.objects if o.station_id.confidence >= 0 and round(o.station_id.value) == 101), None)


def between(scenes, start_s, end_s):
    return [s for s in scenes if start_s <= s.header.sample_time_s < end_s]


def test_through_the_dropout_the_leader_stays_the_forward_mio_under_one_id(scenes):
    mio_ids = {s.forward_mio_id for s in between(scenes, 3.0, ALL_STOP_S) if s.has_forward_mio}
    assert len(mio_ids) == 1
    assert all(s.has_forward_mio for s in between(scenes, 3.0, ALL_STOP_S))
    assert {leader(s).object_id for s in between(scenes, 3.0, ALL_STOP_S)} == mio_ids


def test_during_the_dropout_v2v_alone_holds_it_with_visibly_lower_confidence_and_after_it_recovers(scenes):
    ranging_fade_s = SceneFusionConfig().radar_source.fade_time_s
    before = [leader(s).position.confidence for s in between(scenes, 4.0, DROPOUT_S[0])]
    during = [leader(s).position for s in between(scenes, DROPOUT_S[0] + ranging_fade_s + 0.1, DROPOUT_S[1])]
    after = [leader(s).position.confidence for s in between(scenes, DROPOUT_S[1] + 0.5, ALL_STOP_S)]
    assert during and all(list(p.sources) == [V2V] for p in during)
    assert max(p.confidence for p in during) < min(before) - 0.2
    assert min(after) > max(p.confidence for p in during) + 0.2


def test_when_every_source_stops_each_fades_on_schedule_and_then_the_object_goes(scenes):
    config = SceneFusionConfig()
    ranging_fade_s, v2v_fade_s = config.radar_source.fade_time_s, config.v2v_source.fade_time_s
    margin_s = 0.15
    seen_by_sensors = between(scenes, ALL_STOP_S, ALL_STOP_S + ranging_fade_s - margin_s)
    v2v_only = between(scenes, ALL_STOP_S + ranging_fade_s + margin_s, ALL_STOP_S + v2v_fade_s - margin_s)
    gone = between(scenes, ALL_STOP_S + v2v_fade_s + margin_s, ALL_STOP_S + v2v_fade_s + 1.0)
    assert all(len(leader(s).position.sources) > 1 for s in seen_by_sensors)
    assert v2v_only and all(list(leader(s).position.sources) == [V2V] for s in v2v_only)
    assert gone and all(leader(s) is None and not s.has_forward_mio for s in gone)
