"""The stack's scene, lanes, planned path and the simulator's ground truth as Foxglove SceneUpdates.

Entity ids are namespaced ("<vehicle>/object/<id>", "<vehicle>/path", "truth/<vehicle>", "lane/<lane id>") so
the 3D panel's topic and entity lists stay readable; each update deletes what the previous one on its topic
drew, so an object the scene dropped disappears with it.
"""

from __future__ import annotations

import math

import numpy as np
from foxglove_schemas_protobuf.SceneEntity_pb2 import SceneEntity
from foxglove_schemas_protobuf.SceneEntityDeletion_pb2 import SceneEntityDeletion
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate

from coopdrive.roadmap import RoadMap
from coopdrive.messages.unknowns import DEFAULT_LENGTH_M, DEFAULT_WIDTH_M
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.visual.primitives import (
    MAP_FRAME,
    box,
    color,
    confidence_color,
    label,
    line_strip,
    timestamp,
)
from coopdrive.v1 import ego_pb2, planner_pb2, scene_pb2, sim_pb2

MIO_COLOR = color(1.0, 0.45, 0.0, 0.9)
EGO_COLOR = color(0.2, 0.45, 1.0, 0.9)
TRUTH_COLOR = color(1.0, 1.0, 1.0, 0.35)
LANE_COLOR = color(0.8, 0.8, 0.8, 0.8)
PATH_COLOR = color(0.1, 0.8, 1.0, 1.0)
LABEL_COLOR = color(1.0, 1.0, 1.0, 1.0)
LANE_THICKNESS_PX = 1.5
PATH_THICKNESS_PX = 4.0
# The planned path drawn ahead of the ego, and its spacing.
PATH_LENGTH_M = 60.0
PATH_STEP_M = 2.0


def _replace_all(time_s: float) -> SceneUpdate:
    return SceneUpdate(deletions=[SceneEntityDeletion(timestamp=timestamp(time_s), type=SceneEntityDeletion.ALL)])


def _known(prop: scene_pb2.ScalarProperty, default: float) -> float:
    return prop.value if prop.confidence >= 0.0 and prop.value > 0.0 else default


def object_entity(vehicle_id: str, obj: scene_pb2.SceneObject, is_mio: bool, time_s: float) -> SceneEntity:
    """A box at the object's estimate, shaded by its position confidence, labelled with its id and (when V2V
    linked it) its ITS station."""
    length_m = _known(obj.length_m, DEFAULT_LENGTH_M)
    width_m = _known(obj.width_m, DEFAULT_WIDTH_M)
    heading_rad = obj.heading_rad.value if obj.heading_rad.confidence >= 0.0 else 0.0
    fill = MIO_COLOR if is_mio else confidence_color(obj.position.confidence)
    text = f"{obj.object_id}"
    if obj.station_id.confidence >= 0.0 and obj.station_id.value:
        text += f" / {obj.station_id.value}"
    if is_mio:
        text += " MIO"
    cube = box(obj.position.x_m, obj.position.y_m, heading_rad, length_m, width_m, fill)
    return SceneEntity(timestamp=timestamp(time_s), frame_id=MAP_FRAME, id=f"{vehicle_id}/object/{obj.object_id}",
                       cubes=[cube], texts=[label(cube.pose.position.x, cube.pose.position.y, text, LABEL_COLOR)])


def ego_entity(vehicle_id: str, time_s: float) -> SceneEntity:
    """The ego's own box, locked to its frame (at its rear axle, moved by the map -> vehicle transforms)."""
    return SceneEntity(timestamp=timestamp(time_s), frame_id=vehicle_id, frame_locked=True, id=f"{vehicle_id}/ego",
                       cubes=[box(0.0, 0.0, 0.0, DEFAULT_LENGTH_M, DEFAULT_WIDTH_M, EGO_COLOR,
                                  rear_overhang_m(DEFAULT_LENGTH_M))],
                       texts=[label(DEFAULT_LENGTH_M / 2.0, 0.0, vehicle_id, LABEL_COLOR)])


def planned_path(ego: ego_pb2.EgoState, behaviour: planner_pb2.BehaviourRequest | None,
                 road_map: RoadMap | None) -> list[tuple[float, float]]:
    """Where the planner sends the ego: the centre line of its target lane (shifted by the requested lateral
    offset) ahead of it; without a lane map or a match on one, straight ahead along its heading."""
    steps = int(PATH_LENGTH_M / PATH_STEP_M) + 1
    lane = None
    if road_map is not None and ego.lane.matched and ego.lane.road_id:
        lanes = road_map.lanes_of_road(ego.lane.road_id)
        wanted = behaviour.target_lane_index if behaviour is not None else ego.lane.lane_index
        lane = next((candidate for candidate in lanes if candidate.lane_index == wanted), None)
    if lane is None:
        return [(ego.x_m + k * PATH_STEP_M * math.cos(ego.heading_rad),
                 ego.y_m + k * PATH_STEP_M * math.sin(ego.heading_rad)) for k in range(steps)]
    start_m = lane.project_full(ego.x_m, ego.y_m).station_m
    offset_m = behaviour.lateral_offset_m if behaviour is not None else 0.0
    return [(x_m, y_m) for x_m, y_m in lane.points_at(start_m + PATH_STEP_M * np.arange(steps), offset_m).tolist()]


def scene_update(vehicle_id: str, scene: scene_pb2.Scene, ego: ego_pb2.EgoState | None,
                 behaviour: planner_pb2.BehaviourRequest | None, road_map: RoadMap | None) -> SceneUpdate:
    """One vehicle's perception: its objects (the MIO marked), itself, and its planned path."""
    time_s = scene.header.sample_time_s
    update = _replace_all(time_s)
    mio_id = scene.mio_id if scene.has_mio else None
    update.entities.extend(object_entity(vehicle_id, obj, obj.object_id == mio_id, time_s) for obj in scene.objects)
    if ego is not None:
        update.entities.append(ego_entity(vehicle_id, time_s))
        update.entities.append(SceneEntity(timestamp=timestamp(time_s), frame_id=MAP_FRAME, id=f"{vehicle_id}/path",
                                           lines=[line_strip(planned_path(ego, behaviour, road_map), PATH_COLOR,
                                                             PATH_THICKNESS_PX)]))
    return update


def truth_update(truth: sim_pb2.GroundTruth) -> SceneUpdate:
    """Every simulated vehicle where it really is (its reference point is the rear axle centre, as in the
    simulator's geometry)."""
    time_s = truth.header.sample_time_s
    update = _replace_all(time_s)
    for vehicle in truth.vehicles:
        length_m = vehicle.length_m or DEFAULT_LENGTH_M
        update.entities.append(SceneEntity(
            timestamp=timestamp(time_s), frame_id=MAP_FRAME, id=f"truth/{vehicle.vehicle_id}",
            cubes=[box(vehicle.x_m, vehicle.y_m, vehicle.heading_rad, length_m, vehicle.width_m or DEFAULT_WIDTH_M,
                       TRUTH_COLOR, rear_overhang_m(length_m))],
            texts=[label(vehicle.x_m, vehicle.y_m, f"{vehicle.vehicle_id} ({vehicle.station_id})", TRUTH_COLOR)]))
    return update


def lanes_update(road_map: RoadMap, time_s: float) -> SceneUpdate:
    """The lane map's centre lines."""
    update = _replace_all(time_s)
    update.entities.extend(
        SceneEntity(timestamp=timestamp(time_s), frame_id=MAP_FRAME, id=f"lane/{lane.lane_id}",
                    lines=[line_strip(lane.points_xy, LANE_COLOR, LANE_THICKNESS_PX)])
        for lane in road_map.lanes)
    return update
