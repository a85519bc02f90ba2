import math

import pytest

from coopdrive.services.scene.config import SceneFusionConfig
from coopdrive.services.scene.fusion import SceneFusion
from coopdrive.services.scene.measurement import V2vObservation
from coopdrive.services.scene.track import Track
from coopdrive.v1 import header_pb2, sensors_pb2

from .helpers import Road, ego_state, lidar_scan, radar_tracks, v2v

RADAR = header_pb2.SENSOR_SOURCE_RADAR
LIDAR = header_pb2.SENSOR_SOURCE_LIDAR
V2V = header_pb2.SENSOR_SOURCE_V2V
STATION = 77


def lead_rear_x(time_s: float) -> float:
    """A car 25 m ahead of our rear axle at t = 0, doing 12 m/s."""
    return 25.0 + 12.0 * time_s


def only(scene):
    assert len(scene.objects) == 1, scene
    return scene.objects[0]


def by_station(scene, station_id):
    found = [o for o in scene.objects if o.station_id.confidence > 0 and o.station_id.value == station_id]
    assert len(found) <= 1
    return found[0] if found else None


def test_a_late_v2v_measurement_is_fused_at_its_own_time_not_dropped():
    fusion = SceneFusion()
    road = Road(fusion)
    pending = []
    for t in road.ticks(0.0, 1.5):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)])
        pending.append(v2v(t, STATION, lead_rear_x(t), 0.0, 12.0, accel_mps2=0.4))
        # Each CAM is delivered three ticks (0.15 s) after it was sampled.
        if len(pending) > 3:
            fusion.on_v2v(pending.pop(0))
    obj = only(fusion.scene(1.5))
    assert obj.station_id.value == STATION
    assert V2V in obj.position.sources
    assert obj.accel_mps2.value == pytest.approx(0.4)
    assert fusion.tracker.counters.replayed > 20
    assert fusion.tracker.counters.too_late == 0


def test_during_a_two_second_radar_dropout_the_object_stays_on_v2v_alone_with_lower_confidence_and_the_same_id():
    fusion = SceneFusion()
    road = Road(fusion)
    for t in road.ticks(0.0, 2.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)], lidar=False)
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t), 0.0, 12.0))
    before = only(fusion.scene(2.0))
    assert set(before.position.sources) == {RADAR, V2V}
    for t in road.ticks(2.0, 4.0):
        fusion.on_ego(road.ego(t))
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t), 0.0, 12.0))
        scene = fusion.scene(t)
        obj = only(scene)
        assert obj.object_id == before.object_id
        assert scene.mio_id == before.object_id
        if t >= 2.6:
            assert list(obj.position.sources) == [V2V]
            assert 0.0 < obj.position.confidence < before.position.confidence
            assert obj.position.x_m == pytest.approx(lead_rear_x(t), abs=0.5)
    for t in road.ticks(4.0, 4.5):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)], lidar=False)
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t), 0.0, 12.0))
    back = only(fusion.scene(4.5))
    assert back.object_id == before.object_id
    assert set(back.position.sources) == {RADAR, V2V}


@pytest.mark.parametrize("omit_misses", [False, True], ids=["misses-at-max-range", "misses-left-out"])
def test_a_ghost_station_claiming_a_spot_radar_and_lidar_see_free_is_flagged_and_never_mio(omit_misses):
    fusion = SceneFusion()
    road = Road(fusion, omit_misses=omit_misses)
    ghost_ids, mio_ids = set(), set()
    for t in road.ticks(0.0, 3.0):
        road.sense(t, [(road.ego_x(t) + 50.0, 0.0, 10.0)])
        fusion.on_v2v(v2v(t, 666, road.ego_x(t) + 20.0, 0.0, 10.0))
        scene = fusion.scene(t)
        ghost_ids |= {o.object_id for o in scene.objects if o.ghost}
        if scene.has_mio:
            mio_ids.add(scene.mio_id)
    ghost = by_station(fusion.scene(3.0), 666)
    assert ghost is not None and ghost.ghost
    assert ghost.v2v_trust == 0.0
    # Shown where the station claims to be, so the HMI can draw it, but flagged.
    assert ghost.position.x_m == pytest.approx(Road.EGO_SPEED_MPS * 3.0 + 20.0, abs=0.5)
    assert ghost_ids == {ghost.object_id}
    assert ghost.object_id not in mio_ids
    assert len(mio_ids) == 1  # the car 50 m ahead, seen by both sensors


@pytest.mark.parametrize("offset", [(3.0, 0.0), (0.0, 3.0)], ids=["ahead", "aside"])
def test_a_station_whose_cam_position_is_offset_by_3_m_loses_trust_within_2_s(offset):
    fusion = SceneFusion()
    road = Road(fusion)
    untrusted_at = None
    for t in road.ticks(0.0, 2.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)])
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t) + offset[0], offset[1], 12.0))
        if untrusted_at is None and not fusion.trust.trusted(STATION):
            untrusted_at = t
    assert untrusted_at is not None and untrusted_at <= 2.0
    obj = only(fusion.scene(2.0))
    # Linked, so the object carries the station, but its wrong position was not fused.
    assert obj.station_id.value == STATION
    assert obj.v2v_trust < fusion.config.trust.min_trusted
    assert obj.position.x_m == pytest.approx(lead_rear_x(2.0), abs=0.3)
    assert obj.position.y_m == pytest.approx(0.0, abs=0.3)


def test_an_honest_station_keeps_and_slowly_gains_trust():
    fusion = SceneFusion()
    road = Road(fusion)
    for t in road.ticks(0.0, 2.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)])
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t) + 0.3, 0.0, 12.0))
    trust = fusion.trust.trust(STATION)
    initial = fusion.config.trust.initial
    # Forty messages over 2 s, the first credited 0.1 s: trust climbs at raise_per_s at most.
    assert initial < trust <= initial + fusion.config.trust.raise_per_s * 2.1 + 1e-9


def test_a_single_false_lidar_detection_is_never_published_and_is_gone_within_half_a_second():
    fusion = SceneFusion()
    road = Road(fusion)
    published = set()
    for t in road.ticks(0.0, 2.0):
        objects = [(lead_rear_x(t), 0.0, 12.0)]
        fusion.on_ego(road.ego(t))
        if round(t / road.TICK_S) % 2 == 0:
            boxes = [(x, y, 1.8) for x, y, _ in objects]
            if t == 1.0:
                boxes.append((road.ego_x(t) + 15.0, 3.5, 1.8))
            fusion.on_lidar(lidar_scan(t, boxes, ego_x_m=road.ego_x(t)), road.ego(t))
        published |= {o.object_id for o in fusion.scene(t).objects}
        if t == 1.5:
            assert len(fusion.tracker.tracks) == 1
    assert len(published) == 1


def test_a_short_lived_false_object_disappears_within_half_a_second_of_its_last_detection():
    fusion = SceneFusion()
    road = Road(fusion)
    last_seen = {}
    for t in road.ticks(0.0, 2.0):
        boxes = [(lead_rear_x(t), 0.0, 1.8)]
        if 0.5 <= t <= 0.8:
            boxes.append((road.ego_x(t) + 15.0, 3.5, 1.8))
        if round(t / road.TICK_S) % 2 == 0:
            fusion.on_lidar(lidar_scan(t, boxes, ego_x_m=road.ego_x(t)), road.ego(t))
        for obj in fusion.scene(t).objects:
            last_seen[obj.object_id] = t
    assert len(last_seen) == 2
    false_id = max(last_seen)
    assert last_seen[false_id] <= 0.8 + 0.5


def test_identity_is_kept_through_a_short_lidar_dropout():
    fusion = SceneFusion()
    road = Road(fusion)
    ids = []
    for t in road.ticks(0.0, 2.0):
        visible = not 1.0 <= t < 1.3
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)] if visible else [], radar=False)
        ids += [o.object_id for o in fusion.scene(t).objects]
    assert set(ids) == {ids[0]}


def lanes(x_m, y_m):
    """Two 4 m lanes: index 0 around y = 0, index 1 (left) around y = 4."""
    return 1 if y_m > 2.0 else 0


def test_mio_forward_mio_and_lane_neighbours_follow_the_map_lanes():
    fusion = SceneFusion(lane_of=lanes)
    road = Road(fusion)
    for t in road.ticks(0.0, 1.0):
        ahead = (road.ego_x(t) + 30.0, 0.0, 10.0)
        left_ahead = (road.ego_x(t) + 20.0, 4.0, 10.0)
        road.sense(t, [ahead, left_ahead])
        fusion.on_v2v(v2v(t, 5, road.ego_x(t) - 15.0, 4.0, 10.0))
    scene = fusion.scene(1.0)
    by_gap = {round(o.longitudinal_gap_m): o for o in scene.objects}
    gaps = sorted(by_gap)
    assert len(gaps) == 3
    behind_left, left_ahead, ahead = (by_gap[g] for g in gaps)
    assert scene.ego_lane_index == 0
    assert scene.has_mio and scene.mio_id == ahead.object_id
    assert scene.has_forward_mio and scene.forward_mio_id == ahead.object_id
    left = next(n for n in scene.neighbours if n.lane_offset == 1)
    right = next(n for n in scene.neighbours if n.lane_offset == -1)
    assert left.has_ahead and left.ahead_object_id == left_ahead.object_id
    assert left.has_behind and left.behind_object_id == behind_left.object_id
    assert not right.has_ahead and not right.has_behind
    assert left_ahead.lane_index.value == 1
    assert header_pb2.SENSOR_SOURCE_MAP in left_ahead.lane_index.sources


def test_the_gap_runs_from_the_ego_front_bumper_to_the_object_rear_along_the_lane():
    config = SceneFusionConfig(ego_length_m=5.0, ego_rear_overhang_m=1.2)
    fusion = SceneFusion(config)
    road = Road(fusion)
    for t in road.ticks(0.0, 1.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)])
    obj = only(fusion.scene(1.0))
    ego_front_x = road.ego_x(1.0) + 5.0 - 1.2
    assert obj.longitudinal_gap_m == pytest.approx(lead_rear_x(1.0) - ego_front_x, abs=0.2)
    assert obj.relative_speed_mps == pytest.approx(2.0, abs=0.2)


def test_the_same_calls_give_byte_identical_scenes():
    def run():
        fusion = SceneFusion(lane_of=lanes)
        road = Road(fusion)
        for t in road.ticks(0.0, 1.0):
            road.sense(t, [(lead_rear_x(t), 0.0, 12.0), (road.ego_x(t) + 20.0, 4.0, 10.0)])
            fusion.on_v2v(v2v(t, STATION, lead_rear_x(t), 0.0, 12.0))
        return fusion.scene(1.0).SerializeToString(deterministic=True)

    assert run() == run()


def test_sensor_frames_before_any_ego_state_are_counted_not_fatal():
    fusion = SceneFusion()
    fusion.on_v2v(v2v(0.0, STATION, 20.0, 0.0, 10.0))
    assert fusion.counters()["rejected: v2v: no ego state yet"] == 1
    assert len(fusion.scene(0.0).objects) == 0


def test_a_station_linked_to_the_wrong_car_moves_to_the_car_our_sensors_see_where_it_claims():
    fusion = SceneFusion()
    road = Road(fusion)
    near, far = (lambda t: lead_rear_x(t)), (lambda t: lead_rear_x(t) + 2.5)
    # Only the near car is seen at first, so the station of the far car, 3.9 m off, links to it.
    for t in road.ticks(0.0, 0.2):
        road.sense(t, [(near(t), 0.0, 12.0)])
        fusion.on_v2v(v2v(t, STATION, far(t), 3.0, 12.0))
    first = fusion.tracker.track_of_station(STATION).track_id
    for t in road.ticks(0.2, 1.5):
        road.sense(t, [(near(t), 0.0, 12.0), (far(t), 3.0, 12.0)])
        fusion.on_v2v(v2v(t, STATION, far(t), 3.0, 12.0))
    track = fusion.tracker.track_of_station(STATION)
    assert track.track_id != first
    assert Track.position_of(track.predicted(1.5)[0]) == pytest.approx([far(1.5), 3.0], abs=0.5)


def test_an_ego_state_that_is_not_a_number_is_counted_and_ignored():
    fusion = SceneFusion()
    road = Road(fusion)
    fusion.on_ego(road.ego(0.0))
    bad = road.ego(0.05)
    bad.heading_rad = float("nan")
    fusion.on_ego(bad)
    fusion.on_radar(radar_tracks(0.1, [(lead_rear_x(0.1), 0.0, 12.0)]), bad)
    assert fusion.counters()["rejected: ego state heading_rad is nan"] == 1
    assert fusion.counters()["rejected: radar: ego state heading_rad is nan"] == 1
    fusion.scene(0.1)


def test_on_a_curve_the_gap_runs_along_the_ego_lane_not_the_straight_line():
    radius_m = 100.0

    def along_circle(x_m, y_m):
        """A left-hand lane: circle of radius 100 m centred at (0, 100), starting at the origin heading east."""
        dx, dy = x_m, y_m - radius_m
        return radius_m * math.atan2(dx, -dy), radius_m - math.hypot(dx, dy)

    fusion = SceneFusion(frenet_of=along_circle)
    fusion.on_ego(ego_state(0.0))
    arc_m = 40.0
    angle = arc_m / radius_m
    x, y = radius_m * math.sin(angle), radius_m * (1.0 - math.cos(angle))
    for k in range(4):
        t = 0.1 * k
        fusion.on_v2v(V2vObservation(station_id=3, x_m=x, y_m=y, speed_mps=0.0, heading_rad=angle, accel_mps2=0.0,
                                     length_m=4.5, width_m=1.8, sample_time_s=t))
    # reference_is_front: the CAM point is the front, so the rear lies 4.5 m back along the heading
    (obj,) = fusion.scene(0.3).objects
    front_bumper_m = fusion.config.ego_length_m - fusion.config.ego_rear_overhang_m
    assert obj.longitudinal_gap_m == pytest.approx(arc_m - 4.5 - front_bumper_m, abs=0.1)
    assert obj.lateral_offset_m == pytest.approx(0.0, abs=0.15)


def test_an_offset_station_heard_before_our_sensors_see_its_car_ends_up_as_one_untrusted_object():
    fusion = SceneFusion()
    road = Road(fusion)
    for t in road.ticks(0.0, 1.0):
        fusion.on_ego(road.ego(t))
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t) + 3.0, 0.0, 12.0))
    assert len(fusion.scene(1.0).objects) == 1
    for t in road.ticks(1.0, 3.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)])
        fusion.on_v2v(v2v(t, STATION, lead_rear_x(t) + 3.0, 0.0, 12.0))
    obj = only(fusion.scene(3.0))
    assert obj.station_id.value == STATION
    assert not fusion.trust.trusted(STATION)
    assert obj.position.x_m == pytest.approx(lead_rear_x(3.0), abs=0.3)


def test_a_car_coming_the_other_way_close_to_our_lane_is_never_the_forward_mio_nor_a_neighbour():
    fusion = SceneFusion(lane_of=lambda x_m, y_m: None)  # on another road: lanes from lateral bands
    road = Road(fusion)
    for t in road.ticks(0.0, 1.0):
        road.sense(t, [], lidar=False, radar=False)
        fusion.on_v2v(V2vObservation(station_id=STATION, x_m=80.0 - 10.0 * t, y_m=1.0, speed_mps=10.0,
                                     heading_rad=math.pi, accel_mps2=0.0, length_m=4.5, width_m=1.8,
                                     sample_time_s=t))
    scene = fusion.scene(1.0)
    oncoming = by_station(scene, STATION)
    assert oncoming.longitudinal_gap_m > 0
    assert not (scene.has_forward_mio and scene.forward_mio_id == oncoming.object_id)
    assert all(n.ahead_object_id != oncoming.object_id or not n.has_ahead for n in scene.neighbours)


def test_a_camera_only_object_short_of_the_car_our_radar_holds_is_reported_but_never_takes_the_mio():
    fusion = SceneFusion()
    road = Road(fusion)
    for t in road.ticks(0.0, 1.0):
        road.sense(t, [(road.ego_x(t) + 30.0, 0.0, 10.0)])
        # A monocular camera puts the same car, or a phantom, 8 m short of it.
        frame = sensors_pb2.CameraFrame()
        frame.header.sample_time_s = t
        frame.detections.add(detection_id=1, x_m=22.0, y_m=0.0, width_m=1.8, confidence=0.9)
        fusion.on_camera(frame, road.ego(t))
    scene = fusion.scene(1.0)
    by_gap = sorted(scene.objects, key=lambda o: o.longitudinal_gap_m)
    camera_only, seen = by_gap[0], by_gap[-1]
    assert list(camera_only.position.sources) == [header_pb2.SENSOR_SOURCE_CAMERA]
    assert scene.has_mio and scene.mio_id == seen.object_id
    assert not scene.has_forward_mio or scene.forward_mio_id == seen.object_id


def test_an_object_whose_only_ranging_is_one_radar_false_alarm_is_reported_but_never_takes_the_mio():
    fusion = SceneFusion()
    road = Road(fusion)
    car = lambda t: (road.ego_x(t) + 30.0, 0.0, 10.0)  # noqa: E731
    for t in road.ticks(0.0, 0.5):
        road.sense(t, [car(t)], lidar=False)
    # One radar frame also holds a false alarm standing still 15 m ahead; two camera frames then put a
    # detection on that spot, as noisy bearings of a car beside it would.
    phantom_x_m = road.ego_x(0.5) + 15.0
    road.sense(0.5, [car(0.5), (phantom_x_m, 0.3, 0.0)], lidar=False)
    for t in road.ticks(0.55, 0.7):
        road.sense(t, [car(t)], lidar=False)
        frame = sensors_pb2.CameraFrame()
        frame.header.sample_time_s = t
        frame.detections.add(detection_id=1, x_m=phantom_x_m - road.ego_x(t), y_m=0.3, width_m=1.8, confidence=0.9)
        fusion.on_camera(frame, road.ego(t))
    scene = fusion.scene(0.7)
    by_gap = sorted(scene.objects, key=lambda o: o.longitudinal_gap_m)
    assert len(by_gap) == 2
    phantom, seen = by_gap
    assert set(phantom.position.sources) == {RADAR, header_pb2.SENSOR_SOURCE_CAMERA}
    assert scene.has_mio and scene.mio_id == seen.object_id


def test_a_track_s_speed_and_heading_come_with_standard_deviations_that_shrink_as_its_readings_come_in():
    """Out of its first few LiDAR positions a new track knows its heading to a tenth of a radian, after seconds to
    a few hundredths: the scene says so, and the truth stays within three of them."""
    fusion = SceneFusion()
    road = Road(fusion)
    published = []
    for t in road.ticks(0.0, 3.0):
        road.sense(t, [(lead_rear_x(t), 0.0, 12.0)], radar=False)
        published += [(o.speed_mps, o.heading_rad) for o in fusion.scene(t).objects]
    (first_speed, first_heading), (last_speed, last_heading) = published[0], published[-1]
    assert first_heading.std > 2.0 * last_heading.std > 0.0
    assert first_speed.std > 1.5 * last_speed.std > 0.0
    assert last_heading.std < 0.1 and last_speed.std < 0.5
    assert all(abs(heading.value) <= 3.0 * heading.std and abs(speed.value - 12.0) <= 3.0 * speed.std
               for speed, heading in published)
