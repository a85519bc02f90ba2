"""A seeded, noisy eight-second drive: two cars with V2V, radar and LiDAR noise, false alarms, late CAMs."""

import math

import numpy as np
import pytest

from coopdrive.services.scene.fusion import SceneFusion

from .helpers import ego_state, lidar_scan, radar_tracks, v2v

SEED = 2016
TICK_S = 0.05
DURATION_S = 8.0
EGO_SPEED_MPS = 15.0
CAM_LATENCY_S = (0.05, 0.25)
RADAR_FALSE_ALARM_PROBABILITY = 0.1
LIDAR_CLUTTER_PROBABILITY = 0.1
LEAD, LEFT = 11, 12


def lead(t):
    """Ego lane, 25 m ahead, speed swinging +-1.5 m/s."""
    return 25.0 + EGO_SPEED_MPS * t - 1.5 / 0.8 * (math.cos(0.8 * t) - 1.0), 0.0, EGO_SPEED_MPS + 1.5 * math.sin(0.8 * t)


def left(t):
    """Left lane, 15 m ahead, a little slower."""
    return 15.0 + 14.0 * t, 4.0, 14.0


def lanes(x_m, y_m):
    """Lane 0 between y = -2 and 2, lane 1 between 2 and 6, off the road elsewhere."""
    if -2.0 < y_m <= 2.0:
        return 0
    return 1 if 2.0 < y_m <= 6.0 else None


def drive():
    rng = np.random.default_rng(SEED)
    fusion = SceneFusion(lane_of=lanes)
    inbox = []
    scenes = []
    for k in range(round(DURATION_S / TICK_S)):
        t = k * TICK_S
        ego_x = EGO_SPEED_MPS * t
        ego = ego_state(t, x_m=ego_x, speed_mps=EGO_SPEED_MPS)
        fusion.on_ego(ego)
        cars = [lead(t), left(t)]
        radar = radar_tracks(t, cars, ego_x_m=ego_x, ego_speed_mps=EGO_SPEED_MPS)
        for track in radar.tracks:
            track.range_m += rng.normal(0.0, 0.2)
            track.azimuth_rad += rng.normal(0.0, 0.004)
            track.range_rate_mps += rng.normal(0.0, 0.1)
        if rng.random() < RADAR_FALSE_ALARM_PROBABILITY:
            radar.tracks.add(track_id=99, range_m=rng.uniform(8.0, 60.0), azimuth_rad=rng.uniform(-0.3, 0.3))
        fusion.on_radar(radar, ego)
        if k % 2 == 0:
            boxes = [(x + rng.normal(0.0, 0.05), y, 1.8) for x, y, _ in cars]
            if rng.random() < LIDAR_CLUTTER_PROBABILITY:
                boxes.append((ego_x + rng.uniform(10.0, 40.0), rng.uniform(-5.0, 5.0), 1.5))
            fusion.on_lidar(lidar_scan(t, boxes, ego_x_m=ego_x), ego)
            for station, (x, y, speed) in ((LEAD, cars[0]), (LEFT, cars[1])):
                cam = v2v(t, station, x + rng.normal(0.0, 0.3), y + rng.normal(0.0, 0.3), speed)
                inbox.append((t + rng.uniform(*CAM_LATENCY_S), cam))
        inbox.sort(key=lambda item: item[0])
        while inbox and inbox[0][0] <= t:
            fusion.on_v2v(inbox.pop(0)[1])
        scenes.append((t, fusion.scene(t)))
    return fusion, scenes


@pytest.fixture(scope="module")
def noisy_drive():
    return drive()


def test_a_noisy_drive_keeps_both_cars_ids_and_stations_and_no_false_object_lasts_half_a_second(noisy_drive):
    fusion, scenes = noisy_drive
    settled = [(t, s) for t, s in scenes if t >= 1.0]
    ids_of = {LEAD: set(), LEFT: set()}
    runs, longest = {}, {}
    for t, scene in settled:
        present = set()
        for obj in scene.objects:
            if obj.station_id.confidence > 0.0 and obj.station_id.value in ids_of:
                ids_of[obj.station_id.value].add(obj.object_id)
            present.add(obj.object_id)
        for object_id in present:
            runs.setdefault(object_id, t)
            longest[object_id] = max(longest.get(object_id, 0.0), t - runs[object_id])
        for object_id in list(runs):
            if object_id not in present:
                del runs[object_id]
    assert len(ids_of[LEAD]) == 1 and len(ids_of[LEFT]) == 1
    true_ids = ids_of[LEAD] | ids_of[LEFT]
    false_runs = {i: d for i, d in longest.items() if i not in true_ids}
    assert all(duration <= 0.5 for duration in false_runs.values()), false_runs
    (lead_id,) = ids_of[LEAD]
    (left_id,) = ids_of[LEFT]
    assert all(s.has_mio and s.mio_id == lead_id for _, s in settled)
    assert all(s.forward_mio_id == lead_id for _, s in settled)
    left_lane = [next(n for n in s.neighbours if n.lane_offset == 1) for _, s in settled]
    assert all(n.has_ahead and n.ahead_object_id == left_id for n in left_lane)
    assert fusion.trust.trusted(LEAD) and fusion.trust.trusted(LEFT)
    assert fusion.tracker.counters.replayed > 0 and fusion.tracker.counters.too_late == 0


def test_a_noisy_drive_tracks_the_lead_cars_gap_and_speed(noisy_drive):
    fusion, scenes = noisy_drive
    t, scene = scenes[-1]
    obj = next(o for o in scene.objects if o.object_id == scene.mio_id)
    x, _, speed = lead(t)
    front_bumper_m = fusion.config.ego_length_m - fusion.config.ego_rear_overhang_m
    assert abs(obj.longitudinal_gap_m - (x - EGO_SPEED_MPS * t - front_bumper_m)) < 0.5
    assert abs(obj.relative_speed_mps - (speed - EGO_SPEED_MPS)) < 0.5
    assert obj.accel_mps2.confidence > 0.0
