"""Tracks -> scene_pb2.Scene: properties with confidence, gaps along the ego lane, MIO and neighbours.

MIO: the nearest eligible object ahead inside the ego corridor, half width lane_margin_m / 2
(Heudiasyc Fig. 4), whatever lane the map gives it, so a vehicle cutting in counts as soon as it is in
front of us. Forward MIO: the nearest eligible object ahead in the ego lane by the map (the corridor
when no map answers). Neighbours: nearest ahead and behind in the lanes either side.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from coopdrive.v1 import header_pb2, scene_pb2

from .config import SceneFusionConfig
from .confidence import UNKNOWN_CONFIDENCE, FusedProperty
from .measurement import EgoPose
from .track import Track

LaneOf = Callable[[float, float], "int | None"]
# (x_m, y_m) -> (station_m, lateral_offset_m) on the current ego lane's centre line, or None.
FrenetOf = Callable[[float, float], "tuple[float, float] | None"]
UNKNOWN_LANE = -1
# Below this speed the velocity direction says nothing about heading.
_MIN_SPEED_FOR_HEADING_MPS = 0.5
_LANE_OFFSETS = (-1, 1)
# Faster than this, an object moving against our heading is oncoming traffic.
ONCOMING_MIN_SPEED_MPS = 1.0


@dataclass(frozen=True)
class ObjectView:
    """A confirmed track as the scene sees it: may it be an obstacle, and what its station is worth."""

    track: Track
    eligible: bool
    ghost: bool
    v2v_trust: float


def _larger_std_m(cov: np.ndarray) -> float:
    """Square root of the larger eigenvalue of a symmetric 2x2 covariance."""
    half_trace = 0.5 * (cov[0, 0] + cov[1, 1])
    spread = math.hypot(0.5 * (cov[0, 0] - cov[1, 1]), cov[0, 1])
    return math.sqrt(max(0.0, half_trace + spread))


def _fill_scalar(target: scene_pb2.ScalarProperty, prop: FusedProperty, value: float, time_s: float) -> None:
    confidence = prop.confidence(time_s)
    target.confidence = confidence
    if confidence == UNKNOWN_CONFIDENCE:
        return
    target.value = value
    target.sources.extend(prop.sources(time_s))
    target.valid_until_s = prop.valid_until_s()


class SceneBuilder:
    def __init__(self, config: SceneFusionConfig, lane_of: LaneOf | None, frenet_of: FrenetOf | None = None) -> None:
        self._config = config
        self._lane_of = lane_of
        self._frenet_of = frenet_of

    def lane(self, x_m: float, y_m: float) -> int | None:
        return self._lane_of(x_m, y_m) if self._lane_of is not None else None

    def build(self, time_s: float, ego: EgoPose, views: list[ObjectView], free_ranges_m: list[float]) -> scene_pb2.Scene:
        scene = scene_pb2.Scene()
        scene.header.sample_time_s = time_s
        scene.header.sender = "scene"
        ego_lane = self.lane(ego.x_m, ego.y_m)
        scene.ego_lane_index = ego_lane if ego_lane is not None else UNKNOWN_LANE
        scene.free_space.range_m.extend(free_ranges_m)
        candidates = []
        for view in sorted(views, key=lambda v: v.track.track_id):
            obj, lane = self._object(time_s, ego, view)
            scene.objects.append(obj)
            if view.eligible:
                candidates.append((obj, lane))
        self._pick_mio(scene, candidates, ego_lane, ego.heading_rad)
        same_way = [(obj, lane) for obj, lane in candidates if not _oncoming(obj, ego.heading_rad)]
        self._pick_neighbours(scene, same_way, ego_lane)
        return scene

    def _object(self, time_s: float, ego: EgoPose, view: ObjectView) -> tuple[scene_pb2.SceneObject, int | None]:
        track, props = view.track, view.track.props
        x, p = track.predicted(time_s)
        position = Track.position_of(x)
        velocity = Track.velocity_of(x)
        speed = float(np.linalg.norm(velocity))
        obj = scene_pb2.SceneObject(object_id=track.track_id, first_seen_s=track.first_seen_s)
        obj.object_class = props.object_class_value if not props.object_class.faded(time_s) else 0
        pos_conf = props.position.confidence(time_s)
        obj.position.confidence = pos_conf
        if pos_conf != UNKNOWN_CONFIDENCE:
            obj.position.x_m, obj.position.y_m = float(position[0]), float(position[1])
            obj.position.sources.extend(props.position.sources(time_s))
            obj.position.valid_until_s = props.position.valid_until_s()
            obj.position.std_m = _larger_std_m(Track.position_cov_of(p))
        _fill_scalar(obj.speed_mps, props.speed, speed, time_s)
        heading = math.atan2(velocity[1], velocity[0])
        if speed < _MIN_SPEED_FOR_HEADING_MPS and props.heading.value is not None:
            heading = props.heading.value
        _fill_scalar(obj.heading_rad, props.heading, heading, time_s)
        accel = props.reported_accel_mps2
        if accel is None or not props.accel.has_source(header_pb2.SENSOR_SOURCE_V2V, time_s):
            accel = float(Track.accel_of(x) @ velocity / speed) if speed > _MIN_SPEED_FOR_HEADING_MPS else 0.0
        _fill_scalar(obj.accel_mps2, props.accel, accel, time_s)
        _fill_scalar(obj.length_m, props.length, props.length.value or 0.0, time_s)
        _fill_scalar(obj.width_m, props.width, props.width.value or 0.0, time_s)
        station = props.station_id
        obj.station_id.confidence = station.confidence(time_s)
        if track.station_id is not None and station.confidence(time_s) != UNKNOWN_CONFIDENCE:
            obj.station_id.value = track.station_id
            obj.station_id.sources.extend(station.sources(time_s))
            obj.station_id.valid_until_s = station.valid_until_s()
        lane = self.lane(float(position[0]), float(position[1]))
        obj.lane_index.confidence = UNKNOWN_CONFIDENCE
        if lane is not None and pos_conf != UNKNOWN_CONFIDENCE:
            obj.lane_index.value = lane
            obj.lane_index.confidence = pos_conf
            obj.lane_index.sources.extend(sorted(set(props.position.sources(time_s)) | {header_pb2.SENSOR_SOURCE_MAP}))
            obj.lane_index.valid_until_s = props.position.valid_until_s()
        forward = np.array([math.cos(ego.heading_rad), math.sin(ego.heading_rad)])
        left = np.array([-forward[1], forward[0]])
        rel = position - ego.position_m
        front_bumper_m = self._config.ego_length_m - self._config.ego_rear_overhang_m
        along, across = self._along_ego_lane(ego, position)
        if along is None:
            # No lane geometry: along the ego heading, which on a straight road is the same thing.
            along, across = float(rel @ forward), float(rel @ left)
        obj.longitudinal_gap_m = along - front_bumper_m
        obj.lateral_offset_m = across
        obj.relative_speed_mps = float(velocity @ forward) - ego.speed_mps
        obj.v2v_trust = view.v2v_trust
        obj.v2v_time_s = props.v2v_time_s
        obj.ghost = view.ghost
        return obj, lane

    def _along_ego_lane(self, ego: EgoPose, position: np.ndarray) -> tuple[float | None, float]:
        """Station and lateral offset of the object relative to the ego, on the ego lane's centre line."""
        if self._frenet_of is None:
            return None, 0.0
        ego_frenet = self._frenet_of(ego.x_m, ego.y_m)
        obj_frenet = self._frenet_of(float(position[0]), float(position[1]))
        if ego_frenet is None or obj_frenet is None:
            return None, 0.0
        return obj_frenet[0] - ego_frenet[0], obj_frenet[1] - ego_frenet[1]

    def _in_corridor(self, obj: scene_pb2.SceneObject) -> bool:
        return abs(obj.lateral_offset_m) <= 0.5 * self._config.lidar.lane_margin_m

    def _lane_offset(self, obj: scene_pb2.SceneObject, lane: int | None, ego_lane: int | None) -> int:
        """Lane relative to ours (+1 left): from the map when both are known, else from lateral bands."""
        if lane is not None and ego_lane is not None:
            return lane - ego_lane
        return round(obj.lateral_offset_m / self._config.lidar.lane_margin_m)

    def _pick_mio(self, scene: scene_pb2.Scene, candidates: list, ego_lane: int | None, ego_heading_rad: float) -> None:
        ahead = [(obj.longitudinal_gap_m, obj.object_id, obj, lane) for obj, lane in candidates if obj.longitudinal_gap_m >= 0.0]
        mio = [item for item in ahead if self._in_corridor(item[2])]
        if mio:
            scene.has_mio, scene.mio_id = True, min(mio)[1]
        # A car coming the other way is never the one to follow, whichever lane band it seems to be in.
        forward = [item for item in ahead if self._lane_offset(item[2], item[3], ego_lane) == 0
                   and not _oncoming(item[2], ego_heading_rad)]
        if forward:
            scene.has_forward_mio, scene.forward_mio_id = True, min(forward)[1]

    def _pick_neighbours(self, scene: scene_pb2.Scene, candidates: list, ego_lane: int | None) -> None:
        for offset in _LANE_OFFSETS:
            entry = scene_pb2.LaneNeighbours(lane_offset=offset)
            in_lane = [(obj.longitudinal_gap_m, obj.object_id) for obj, lane in candidates if self._lane_offset(obj, lane, ego_lane) == offset]
            ahead = [item for item in in_lane if item[0] >= 0.0]
            behind = [item for item in in_lane if item[0] < 0.0]
            if ahead:
                entry.has_ahead, entry.ahead_object_id = True, min(ahead)[1]
            if behind:
                entry.has_behind, entry.behind_object_id = True, max(behind)[1]
            scene.neighbours.append(entry)


def _oncoming(obj: scene_pb2.SceneObject, ego_heading_rad: float) -> bool:
    """Moving against the ego's direction (a standing object has no direction to judge)."""
    moving = obj.speed_mps.confidence >= 0 and obj.speed_mps.value > ONCOMING_MIN_SPEED_MPS
    return moving and obj.heading_rad.confidence >= 0 and math.cos(obj.heading_rad.value - ego_heading_rad) < 0.0
