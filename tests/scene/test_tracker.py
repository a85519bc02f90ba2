import numpy as np

from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.services.scene.measurement import Measurement
from coopdrive.services.scene.tracker import Tracker
from coopdrive.v1 import header_pb2

LIDAR = header_pb2.SENSOR_SOURCE_LIDAR


def reading(time_s, x_m, ambiguous=False):
    return Measurement(source=LIDAR, time_s=time_s, position_m=np.array([x_m, 2.0]), cov_m2=np.eye(2) * 0.01,
                       origin_m=np.zeros(2), ambiguous=ambiguous)


def test_ambiguous_readings_alone_never_start_an_object():
    tracker = Tracker(SceneFusionConfig())
    for k in range(10):
        tracker.process([reading(0.1 * k, 10.0, ambiguous=True)])
    assert tracker.tracks == {}
    assert tracker.counters.ambiguous_unmatched == 10


def test_ambiguous_readings_refine_a_tentative_track_but_do_not_confirm_it():
    tracker = Tracker(SceneFusionConfig())
    tracker.process([reading(0.0, 10.0)])
    for k in range(1, 6):
        tracker.process([reading(0.05 * k, 10.0, ambiguous=True)])
    (track,) = tracker.tracks.values()
    assert track.hits == 1
    assert tracker.confirmed() == []
    assert track.time_s == 0.25
    # Ordinary readings confirm it as before.
    tracker.process([reading(0.3, 10.0)])
    tracker.process([reading(0.35, 10.0)])
    assert [t.track_id for t in tracker.confirmed()] == [track.track_id]
