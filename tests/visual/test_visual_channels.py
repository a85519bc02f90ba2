"""The channels Foxglove draws, derived from stack messages with no bus: fed by hand, collected by a callback."""

import math

import pytest
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.LocationFix_pb2 import LocationFix
from foxglove_schemas_protobuf.SceneEntityDeletion_pb2 import SceneEntityDeletion
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate

from coopdrive.roadmap import RoadMap
from coopdrive.visual import VisualChannels, recorded_road_map
from coopdrive.visual.channels import GROUND_TRUTH_TOPIC, MAP_TOPIC, TRANSFORMS_TOPIC
from coopdrive.v1 import ego_pb2, gnss_pb2, its_pb2, planner_pb2, scene_pb2, sim_pb2

S = 1_000_000_000


class Collected:
    def __init__(self):
        self.items: list[tuple[str, object, int]] = []

    def __call__(self, topic, message, time_ns):
        self.items.append((topic, message, time_ns))

    def on(self, topic):
        return [message for name, message, _ in self.items if name == topic]


def ego_state(time_s=1.0, x_m=10.0, y_m=2.0, heading_rad=0.0, road_map=None) -> ego_pb2.EgoState:
    ego = ego_pb2.EgoState(x_m=x_m, y_m=y_m, heading_rad=heading_rad, speed_mps=20.0,
                           latitude_deg=51.47, longitude_deg=5.62, covariance=[0.0] * 36)
    ego.covariance[0], ego.covariance[1], ego.covariance[7] = 0.04, 0.01, 0.09
    ego.header.sample_time_s = ego.header.sent_time_s = time_s
    if road_map is not None:
        match = road_map.match(x_m, y_m, heading_rad)
        ego.lane.matched, ego.lane.road_id, ego.lane.lane_index = True, match.lane.road_id, match.lane_index
    return ego


def scene_with(objects, mio_id=None, time_s=1.0) -> scene_pb2.Scene:
    scene = scene_pb2.Scene(has_mio=mio_id is not None, mio_id=mio_id or 0)
    scene.header.sample_time_s = scene.header.sent_time_s = time_s
    for object_id, x_m, confidence, station in objects:
        obj = scene.objects.add(object_id=object_id)
        obj.position.x_m, obj.position.y_m, obj.position.confidence = x_m, 2.0, confidence
        obj.length_m.value, obj.length_m.confidence = 4.0, 0.9
        obj.width_m.value, obj.width_m.confidence = 1.8, 0.9
        obj.station_id.value, obj.station_id.confidence = station, (0.8 if station else -1.0)
    return scene


def test_each_ego_estimate_gives_one_location_fix_at_its_latitude_and_longitude_and_one_map_to_vehicle_transform():
    out = Collected()
    channels = VisualChannels(out)
    channels.on_message("coopdrive/a1/ego/state", ego_state(heading_rad=math.pi / 2), 5 * S)
    channels.flush()
    [fix] = out.on("foxglove/a1/ego")
    assert (fix.latitude, fix.longitude, fix.frame_id) == (51.47, 5.62, "a1")
    assert fix.heading == pytest.approx(0.0)  # ENU north is compass 0
    assert fix.position_covariance_type == LocationFix.KNOWN
    assert list(fix.position_covariance)[:2] == [0.04, 0.01] and fix.position_covariance[4] == 0.09
    [transforms] = out.on(TRANSFORMS_TOPIC)
    [transform] = transforms.transforms
    assert (transform.parent_frame_id, transform.child_frame_id) == ("map", "a1")
    assert (transform.translation.x, transform.translation.y) == (10.0, 2.0)
    assert transform.rotation.z == pytest.approx(math.sin(math.pi / 4))
    assert all(time_ns == 5 * S for _, _, time_ns in out.items)


def test_raw_gnss_fixes_and_every_v2x_station_heard_become_location_fixes():
    out = Collected()
    channels = VisualChannels(out)
    fix = gnss_pb2.GnssFix(latitude_deg=51.0, longitude_deg=5.0, std_east_m=0.5, std_north_m=0.4)
    channels.on_message("coopdrive/a1/gnss/fix", fix, S)
    heard = its_pb2.CamContent(station_id=3002)
    heard.reference_position.latitude_deg, heard.reference_position.longitude_deg = 51.1, 5.1
    channels.on_message("coopdrive/a1/v2x/cam", heard, S)
    channels.on_message("coopdrive/a1/v2x/cam", its_pb2.CamContent(station_id=3003), S)  # position unavailable
    channels.flush()
    [gnss] = out.on("foxglove/a1/gnss")
    assert (gnss.latitude, gnss.position_covariance_type) == (51.0, LocationFix.DIAGONAL_KNOWN)
    assert gnss.position_covariance[0] == pytest.approx(0.25)
    [station] = out.on("foxglove/a1/v2x_stations")
    assert (station.frame_id, station.latitude, station.longitude) == ("station 3002", 51.1, 5.1)


def test_each_epoch_of_the_receiver_s_nmea_bytes_becomes_one_location_fix():
    from coopdrive.gnss.nmea_decoder import with_checksum

    out = Collected()
    channels = VisualChannels(out)
    for second, latitude in ((10, "5128.548"), (11, "5128.549")):
        lines = [with_checksum(f"GPGGA,1200{second}.00,{latitude},N,00537.482,E,4,12,0.8,20.0,M,47.0,M,,"),
                 with_checksum(f"GPRMC,1200{second}.00,A,{latitude},N,00537.482,E,10.0,90.0,250926,,,D"),
                 with_checksum(f"GPGST,1200{second}.00,0.5,0.02,0.02,0,0.02,0.03,0.05")]
        chunk = gnss_pb2.NmeaChunk(data=("\r\n".join(lines) + "\r\n").encode())
        chunk.header.sample_time_s = float(second)
        channels.on_message("coopdrive/a1/gnss/nmea", chunk, second * S)
    channels.flush()
    fixes = out.on("foxglove/a1/gnss")
    assert [round(f.latitude, 5) for f in fixes] == [round(51 + 28.548 / 60, 5), round(51 + 28.549 / 60, 5)]
    assert [time_ns for topic, _, time_ns in out.items if topic == "foxglove/a1/gnss"] == [10 * S, 11 * S]


def test_a_scene_becomes_one_update_with_a_box_per_object_shaded_by_confidence_labelled_and_the_mio_marked():
    out = Collected()
    channels = VisualChannels(out)
    channels.on_message("coopdrive/a1/ego/state", ego_state(), S)
    channels.on_message("coopdrive/a1/scene", scene_with([(4, 30.0, 0.9, 3001), (7, 60.0, 0.2, 0)], mio_id=4), S)
    channels.flush()
    [update] = out.on("foxglove/a1/scene")
    assert [d.type for d in update.deletions] == [SceneEntityDeletion.ALL]  # what the scene dropped goes
    objects = {e.id: e for e in update.entities if "/object/" in e.id}
    assert set(objects) == {"a1/object/4", "a1/object/7"}
    assert objects["a1/object/4"].texts[0].text == "4 / 3001 MIO"
    assert objects["a1/object/7"].texts[0].text == "7"
    cube = objects["a1/object/7"].cubes[0]
    assert cube.pose.position.x == pytest.approx(62.0)  # reference point is the rear face: centre 2 m ahead
    confident = objects["a1/object/4"].cubes[0].color
    assert objects["a1/object/7"].cubes[0].color.a < 0.5 and confident.r > confident.g  # the MIO is orange
    ids = {e.id for e in update.entities}
    assert {"a1/ego", "a1/path"} <= ids


def test_the_planned_path_follows_the_target_lane_of_the_behaviour_request_on_the_lane_map():
    road_map = RoadMap.load("a270")
    lane = road_map.lanes_of_road(road_map.lanes[0].road_id)[0]
    x_m, y_m, heading_rad = lane.pose_at(200.0)
    out = Collected()
    channels = VisualChannels(out, road_map)
    channels.on_message("coopdrive/a1/ego/state", ego_state(x_m=x_m, y_m=y_m, heading_rad=heading_rad,
                                                            road_map=road_map), S)
    other = next(candidate for candidate in road_map.lanes_of_road(lane.road_id) if candidate is not lane)
    channels.on_message("coopdrive/a1/planner/behaviour",
                        planner_pb2.BehaviourRequest(target_lane_index=other.lane_index), S)
    channels.on_message("coopdrive/a1/scene", scene_with([]), S)
    channels.flush()
    [update] = out.on("foxglove/a1/scene")
    [path] = [e for e in update.entities if e.id == "a1/path"]
    end = path.lines[0].points[-1]
    assert abs(other.project_full(end.x, end.y).lateral_offset_m) < 0.01
    assert abs(lane.project_full(end.x, end.y).lateral_offset_m) > 2.0
    [lanes] = out.on(MAP_TOPIC)
    assert {e.id for e in lanes.entities} == {f"lane/{lane.lane_id}" for lane in road_map.lanes}


def test_ground_truth_goes_to_its_own_topic_and_namespace():
    out = Collected()
    truth = sim_pb2.GroundTruth(vehicles=[sim_pb2.VehicleTruth(vehicle_id="a1", station_id=3001, x_m=5.0,
                                                               length_m=4.0, width_m=1.8)])
    channels = VisualChannels(out)
    channels.on_message("coopdrive/world/ground_truth", truth, S)
    channels.flush()
    [update] = out.on(GROUND_TRUTH_TOPIC)
    assert [e.id for e in update.entities] == ["truth/a1"]
    assert update.entities[0].cubes[0].pose.position.x == pytest.approx(5.0 + 2.0 - 0.8)  # rear axle reference


def test_messages_foxglove_does_not_draw_and_keys_outside_the_stack_give_nothing():
    out = Collected()
    channels = VisualChannels(out)
    channels.on_message("coopdrive/a1/control/command", ego_pb2.EgoState(), S)
    channels.on_message("elsewhere", ego_pb2.EgoState(), S)
    channels.flush()
    assert out.items == []


def test_the_recorded_lane_map_is_the_one_geolocation_ran_with():
    assert recorded_road_map({"a1/geolocation": '{"map_name": "a270"}'}).name == "a270"
    assert recorded_road_map({"ego/geolocation": '{"map_name": null}'}) is None
    assert recorded_road_map({}) is None


def test_every_derived_message_is_a_foxglove_schema():
    out = Collected()
    channels = VisualChannels(out, RoadMap.load("a270"))
    channels.on_message("coopdrive/a1/ego/state", ego_state(), S)
    channels.on_message("coopdrive/a1/scene", scene_with([(1, 20.0, 0.5, 0)]), S)
    channels.flush()
    names = {type(message).DESCRIPTOR.full_name for _, message, _ in out.items}
    assert names == {"foxglove.LocationFix", "foxglove.FrameTransforms", "foxglove.SceneUpdate"}
    assert all(isinstance(message, (LocationFix, FrameTransforms, SceneUpdate)) for _, message, _ in out.items)


def drawn_scenes(arrivals) -> list[bytes]:
    out = Collected()
    channels = VisualChannels(out)
    for key, message in arrivals:
        channels.on_message(key, message, round(message.header.sent_time_s * S))
    channels.flush()
    return [update.SerializeToString(deterministic=True) for update in out.on("foxglove/a1/scene")]


def test_a_scene_is_drawn_with_the_ego_estimate_of_its_own_step_in_any_arrival_order():
    """The pipeline's order (geolocation, scene, planner), not arrival order: a replay, whose file holds the same
    messages in another order, draws what the recording drew."""
    step_messages = []
    for step, x_m in ((1, 10.0), (2, 10.4)):
        ego = ego_state(time_s=step * 0.02, x_m=x_m)
        ego.header.sender = "geolocation"
        scene = scene_with([], time_s=step * 0.02)
        scene.header.sender = "scene"
        plan = planner_pb2.BehaviourRequest(lateral_offset_m=step)
        plan.header.sent_time_s, plan.header.sender = step * 0.02, "planner"
        step_messages.append([("coopdrive/a1/ego/state", ego), ("coopdrive/a1/scene", scene),
                              ("coopdrive/a1/planner/behaviour", plan)])
    pipeline_order = [item for step in step_messages for item in step]
    reversed_within_steps = [item for step in step_messages for item in reversed(step)]
    drawn = drawn_scenes(pipeline_order)
    assert drawn_scenes(reversed_within_steps) == drawn and len(drawn) == 2
    [_, second] = [SceneUpdate.FromString(update) for update in drawn]
    [path] = [e for e in second.entities if e.id == "a1/path"]
    assert path.lines[0].points[0].x == pytest.approx(10.4)  # the ego of its own step, not the step before
