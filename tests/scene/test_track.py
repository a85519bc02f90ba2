import numpy as np
import pytest

from coopdrive.services.scene.config import SceneFusionConfig, TrackingConfig
from coopdrive.services.scene.measurement import Measurement
from coopdrive.services.scene.properties import ObjectProperties
from coopdrive.services.scene.track import Track, predict_positions
from coopdrive.v1 import header_pb2

CONFIG = SceneFusionConfig()


def meas(time_s, x_m, source=header_pb2.SENSOR_SOURCE_RADAR, velocity=None):
    return Measurement(source=source, time_s=time_s, position_m=np.array([x_m, 0.5]),
                       cov_m2=np.eye(2) * 0.04, origin_m=np.zeros(2),
                       velocity_mps=None if velocity is None else np.array([velocity, 0.0]),
                       velocity_std_mps=0.3)


def new_track(first, tracking=None):
    tracking = tracking or CONFIG.tracking
    return Track(1, first, tracking, ObjectProperties(CONFIG.source, tracking))


def object_at(time_s):
    return 20.0 + 10.0 * time_s


def test_a_late_measurement_gives_the_same_state_as_if_it_had_arrived_in_order():
    times = [0.0, 0.1, 0.2, 0.3, 0.4]
    late = meas(0.25, object_at(0.25) + 0.3, source=header_pb2.SENSOR_SOURCE_V2V, velocity=10.0)
    in_order = new_track(meas(0.0, object_at(0.0)))
    for t in times[1:]:
        if t == 0.3:
            in_order.apply(late)
        in_order.apply(meas(t, object_at(t)))
    out_of_order = new_track(meas(0.0, object_at(0.0)))
    for t in times[1:]:
        out_of_order.apply(meas(t, object_at(t)))
    assert out_of_order.apply(late)
    assert out_of_order.replays == 1
    x_a, p_a = in_order.predicted(0.5)
    x_b, p_b = out_of_order.predicted(0.5)
    assert x_b == pytest.approx(x_a)
    assert p_b == pytest.approx(p_a)


def test_a_late_measurement_changes_the_estimate():
    track = new_track(meas(0.0, object_at(0.0)))
    for t in (0.1, 0.2, 0.3):
        track.apply(meas(t, object_at(t)))
    before = track.predicted(0.3)[0].copy()
    track.apply(meas(0.15, object_at(0.15), source=header_pb2.SENSOR_SOURCE_V2V, velocity=14.0))
    assert track.predicted(0.3)[0][1] > before[1]


def test_a_measurement_older_than_the_replay_window_is_refused():
    tracking = TrackingConfig(replay_window_s=0.3)
    track = new_track(meas(0.0, object_at(0.0)), tracking)
    for k in range(1, 11):
        track.apply(meas(0.1 * k, object_at(0.1 * k)))
    assert not track.apply(meas(0.2, object_at(0.2)))


def test_the_filter_estimates_speed_from_positions_alone():
    track = new_track(meas(0.0, object_at(0.0), source=header_pb2.SENSOR_SOURCE_LIDAR))
    for k in range(1, 21):
        track.apply(meas(0.1 * k, object_at(0.1 * k), source=header_pb2.SENSOR_SOURCE_LIDAR))
    x, _ = track.predicted(2.0)
    assert x[1] == pytest.approx(10.0, abs=0.3)


def test_a_closer_reading_pulls_the_estimate_more_than_a_further_one_by_the_same_amount():
    def pulled(offset_m):
        track = new_track(meas(0.0, 20.0))
        track.apply(meas(0.1, 20.0 + offset_m))
        return abs(Track.position_of(track.predicted(0.1)[0])[0] - 20.0)

    assert pulled(-1.0) > pulled(1.0)


def test_batch_prediction_for_gating_matches_each_tracks_own_prediction():
    tracks = [new_track(meas(0.0, 20.0)), new_track(meas(0.1, 40.0, velocity=5.0))]
    for k in range(1, 6):
        tracks[0].apply(meas(0.1 * k, object_at(0.1 * k)))
    xy, cov = predict_positions(tracks, 0.9, CONFIG.tracking.jerk_psd_m2ps5)
    for track, got_xy, got_cov in zip(tracks, xy, cov, strict=True):
        x, p = track.predicted(0.9)
        assert got_xy == pytest.approx(Track.position_of(x))
        assert got_cov == pytest.approx(Track.position_cov_of(p))


@pytest.mark.parametrize("late_s", [0.05, 0.25])
def test_a_moved_track_replays_a_late_reading_as_if_its_sensors_had_seen_the_point_it_was_moved_to(late_s):
    """The tracker moves a track started from a car's front back to its rear (front_faces.py); a CAM that comes late
    then replays over sensor readings that are all of the rear (from the first reading, 0.05 s, or a later one)."""
    offset_m = np.array([4.5, 0.0])
    late = meas(late_s, object_at(late_s) + offset_m[0], source=header_pb2.SENSOR_SOURCE_V2V, velocity=10.0)
    moved = new_track(meas(0.0, object_at(0.0)))
    rear = new_track(meas(0.0, object_at(0.0) + offset_m[0]))
    for t in (0.1, 0.2, 0.3):
        moved.apply(meas(t, object_at(t)))
        rear.apply(meas(t, object_at(t) + offset_m[0]))
    moved.move(offset_m)
    assert moved.apply(late) and rear.apply(late)
    assert moved.replays == rear.replays == 1
    x_moved, p_moved = moved.predicted(0.4)
    x_rear, p_rear = rear.predicted(0.4)
    assert x_moved == pytest.approx(x_rear)
    assert p_moved == pytest.approx(p_rear)
    assert moved.ranging_fix.position_m == pytest.approx(rear.ranging_fix.position_m)
