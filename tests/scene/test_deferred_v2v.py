"""A step's CAMs, one from each station, are filtered in one pass (Tracker.fuse_v2v with defer=True): the scene
must be the one that fusing each CAM as it comes gives, to the bit."""

import numpy as np

from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.services.scene.frontends import RejectCounter, V2vFrontEnd
from coopdrive.services.scene.fusion import SceneFusion
from coopdrive.services.scene.measurement import EgoPose
from coopdrive.services.scene.tracker import Tracker

from .helpers import Road, v2v

# Five cars ahead, each a station: two in our lane, two beside us, one our sensors do not reach (V2V alone).
CARS = [(101, 25.0, 0.0, 12.0), (102, 45.0, 0.0, 12.5), (103, 30.0, 3.5, 11.0), (104, 140.0, 3.5, 13.0),
        (105, 55.0, 3.5, 12.0)]
SEEN_RANGE_M = 80.0
# An offset station (its CAMs 3 m off where our sensors see its car), a late one (its CAMs 0.15 s old), and one
# that sends two CAMs a step, 0.02 s apart.
OFFSET_STATION, OFFSET_M = 103, 3.0
LATE_STATION, LATE_S = 102, 0.15
TWICE_STATION, TWICE_LATER_S = 101, 0.02


def rear_x(x0_m: float, speed_mps: float, time_s: float) -> float:
    return x0_m + speed_mps * time_s


def fusing_each_cam_at_once() -> SceneFusion:
    """A scene service whose tracker fuses every V2V reading as it comes, as before readings were deferred."""
    fusion = SceneFusion()
    fuse_v2v = fusion._tracker.fuse_v2v
    fusion._tracker.fuse_v2v = lambda *args, defer=False, **kwargs: fuse_v2v(*args, **kwargs)
    return fusion


def drive(fusion: SceneFusion) -> list[bytes]:
    """The scenes of a 3 s drive, every step's CAMs delivered one after the other, as the radio hands them on."""
    road = Road(fusion)
    scenes = []
    for t in road.ticks(0.0, 3.0):
        seen = [(rear_x(x0, v, t), y, v) for _, x0, y, v in CARS if rear_x(x0, v, t) - road.ego_x(t) < SEEN_RANGE_M]
        road.sense(t, seen)
        cams = [(station, max(0.0, t - LATE_S) if station == LATE_STATION else t, x0, y, speed)
                for station, x0, y, speed in CARS]
        cams.insert(1, (TWICE_STATION, t + TWICE_LATER_S, *CARS[0][1:]))
        for station, sampled_s, x0, y, speed in cams:
            offset_m = OFFSET_M if station == OFFSET_STATION else 0.0
            fusion.on_v2v(v2v(sampled_s, station, rear_x(x0, speed, sampled_s) + offset_m, y, speed))
        scenes.append(fusion.scene(t).SerializeToString())
    return scenes


def test_cams_filtered_together_give_the_scenes_of_cams_fused_one_at_a_time():
    together, one_at_a_time = drive(SceneFusion()), drive(fusing_each_cam_at_once())
    assert len(together) == 60
    assert together == one_at_a_time


def test_the_drive_defers_most_cams_and_replays_the_late_station_s():
    fusion = SceneFusion()
    deferred = []
    flush = fusion._tracker.flush_v2v

    def counting_flush():
        deferred.append(len(fusion._tracker._deferred_v2v))
        flush()

    fusion._tracker.flush_v2v = counting_flush
    drive(fusion)
    # The CAMs of the three honest stations on time wait and go through one pass a step; the late station's are
    # replayed, and the offset station's, which disagree with our sensors, are not fused.
    assert deferred.count(3) >= 55 and max(deferred) == 3
    counters = fusion.tracker.counters
    assert counters.replayed >= 55 and counters.v2v_not_fused >= 55


def cam(time_s: float, x_m: float):
    """Station 7's CAM at time_s, its rear at x_m, as the scene's V2V front end makes it a measurement."""
    config = SceneFusionConfig()
    pose = EgoPose.from_state(Road(None).ego(time_s))
    return V2vFrontEnd(config.v2v, RejectCounter()).measurement(v2v(time_s, 7, x_m, 0.0, 12.0), pose)


def linked_tracker() -> tuple[Tracker, int]:
    """A tracker holding one V2V-only object, station 7's, at 0.1 s."""
    tracker = Tracker(SceneFusionConfig())
    for t in (0.0, 0.1):
        meas = cam(t, 30.0 + 12.0 * t)
        tracker.fuse_v2v(meas, tracker.link_v2v(meas), 1.0, fuse_kinematics=True, scale_covariance=False)
    return tracker, tracker.track_of_station(7).track_id


def deferred(tracker: Tracker) -> None:
    """Station 7's CAM of 0.2 s, fused with defer=True."""
    meas = cam(0.2, 32.4)
    tracker.fuse_v2v(meas, tracker.link_v2v(meas), 1.0, fuse_kinematics=True, scale_covariance=False, defer=True)


def test_a_deferred_reading_leaves_its_track_alone_until_the_flush_and_then_equals_one_fused_at_once():
    (tracker, track_id), (reference, _) = linked_tracker(), linked_tracker()
    before = tracker.tracks[track_id].mean.copy()
    deferred(tracker)
    assert tracker.awaits_v2v(7) and not tracker.awaits_v2v(8)
    assert np.array_equal(tracker.tracks[track_id].mean, before)
    meas = cam(0.2, 32.4)
    reference.fuse_v2v(meas, reference.link_v2v(meas), 1.0, fuse_kinematics=True, scale_covariance=False)
    tracker.flush_v2v()
    assert not tracker.awaits_v2v(7)
    assert np.array_equal(tracker.tracks[track_id].mean, reference.tracks[track_id].mean)
    assert np.array_equal(tracker.tracks[track_id].cov, reference.tracks[track_id].cov)
    assert tracker.tracks[track_id].hits == reference.tracks[track_id].hits == 3


def test_every_reading_of_the_tracker_s_objects_fuses_what_waits_first():
    for read in (lambda tracker: tracker.confirmed(), lambda tracker: tracker.expire(0.2),
                 lambda tracker: tracker.process([]), lambda tracker: tracker.track_of_station(7),
                 lambda tracker: tracker.merge_duplicates(0.2)):
        tracker, _ = linked_tracker()
        deferred(tracker)
        read(tracker)
        assert not tracker.awaits_v2v(7)
