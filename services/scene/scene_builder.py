"""Tracks -> scene_pb2.Scene: properties with confidence, gaps along the ego lane, MIO and neighbours.

The confirmed tracks come as one TrackSnapshot: their kinematics, gaps and lanes are worked out as arrays
for all objects at once, and only filling in the protobuf objects goes one object at a time. The MIO and the
lane neighbours are picked in scene_picks.py.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from operator import attrgetter

import numpy as np

from coopdrive.v1 import header_pb2, scene_pb2

from .config import SceneFusionConfig
from .confidence import UNKNOWN_CONFIDENCE
from . import kalman
from .kalman import IAX, IAY, IVX, IVY, IX, IY
from .measurement import EgoPose
from .occupancy import MIN_SPEED_FOR_HEADING_MPS
from .properties import ACCEL, HEADING, LENGTH, OBJECT_CLASS, POSITION, SPEED, STATION_ID, WIDTH
from .scene_picks import Candidates, pick_mio, pick_neighbours
from .track_snapshot import TrackSnapshot

LaneOf = Callable[[float, float], "int | None"]
# (x_m, y_m) -> (station_m, lateral_offset_m) on the current ego lane's centre line, or None.
FrenetOf = Callable[[float, float], "tuple[float, float] | None"]
UNKNOWN_LANE = -1
# Faster than this, an object moving against our heading is oncoming traffic.
ONCOMING_MIN_SPEED_MPS = 1.0
_MAP_BIT = 1 << header_pb2.SENSOR_SOURCE_MAP
_V2V = header_pb2.SENSOR_SOURCE_V2V
_sources_of = TrackSnapshot.sources_of
# The scalar properties of a SceneObject and their slots in the property table.
_SCALARS = ((attrgetter("speed_mps"), SPEED), (attrgetter("heading_rad"), HEADING), (attrgetter("accel_mps2"), ACCEL),
            (attrgetter("length_m"), LENGTH), (attrgetter("width_m"), WIDTH))


@dataclass(frozen=True)
class ObjectViews:
    """The confirmed tracks as the scene sees them: may each be an obstacle, and what its station is worth."""

    snapshot: TrackSnapshot
    eligible: np.ndarray  # (N,) bool
    ghost: np.ndarray  # (N,) bool
    v2v_trust: list[float]


@dataclass
class _Kinematics:
    """Per object: position, speed, heading, acceleration along the velocity, the standard deviations of speed
    and heading, the larger position std, and where it is relative to us (along and across our lane, speed along
    our heading)."""

    position_m: np.ndarray
    speed_mps: np.ndarray
    heading_rad: np.ndarray
    accel_mps2: np.ndarray
    speed_std_mps: np.ndarray
    heading_std_rad: np.ndarray
    std_m: np.ndarray
    along_m: np.ndarray
    across_m: np.ndarray
    relative_speed_mps: np.ndarray


class SceneBuilder:
    def __init__(self, config: SceneFusionConfig, lane_of: LaneOf | None, frenet_of: FrenetOf | None = None) -> None:
        self._config = config
        self._lane_of = lane_of
        self._frenet_of = frenet_of

    def lane(self, x_m: float, y_m: float) -> int | None:
        return self._lane_of(x_m, y_m) if self._lane_of is not None else None

    def build(self, time_s: float, ego: EgoPose, views: ObjectViews, free_ranges_m: list[float]) -> scene_pb2.Scene:
        scene = scene_pb2.Scene()
        scene.header.sample_time_s = time_s
        scene.header.sender = "scene"
        ego_lane = self.lane(ego.x_m, ego.y_m)
        scene.ego_lane_index = ego_lane if ego_lane is not None else UNKNOWN_LANE
        scene.free_space.range_m.extend(free_ranges_m)
        kinematics = self._kinematics(ego, views.snapshot)
        lanes = [self.lane(x, y) for x, y in kinematics.position_m.tolist()]
        self._objects(scene, views, kinematics, lanes)
        margin_m = self._config.lidar.lane_margin_m
        lane_offset = np.round(kinematics.across_m / margin_m)
        if ego_lane is not None:
            lane_offset = np.array([o if lane is None else lane - ego_lane for o, lane in zip(lane_offset, lanes)])
        confidence = views.snapshot.confidence
        moving = (confidence[:, SPEED] >= 0.0) & (kinematics.speed_mps > ONCOMING_MIN_SPEED_MPS)
        against = (confidence[:, HEADING] >= 0.0) & (np.cos(kinematics.heading_rad - ego.heading_rad) < 0.0)
        candidates = Candidates(np.array([t.track_id for t in views.snapshot.tracks], dtype=int),
                                kinematics.along_m - self._front_bumper_m(), kinematics.across_m, lane_offset,
                                views.eligible, moving & against)
        pick_mio(scene, candidates, 0.5 * margin_m)
        pick_neighbours(scene, candidates)
        return scene

    def _front_bumper_m(self) -> float:
        return self._config.ego_length_m - self._config.ego_rear_overhang_m

    def _kinematics(self, ego: EgoPose, snapshot: TrackSnapshot) -> _Kinematics:
        x, p = snapshot.mean, snapshot.cov
        position, velocity = x[:, [IX, IY]], x[:, [IVX, IVY]]
        speed = np.sqrt(velocity[:, 0] ** 2 + velocity[:, 1] ** 2)
        heading = np.arctan2(velocity[:, 1], velocity[:, 0])
        blended = snapshot.values[:, HEADING]
        heading = np.where((speed < MIN_SPEED_FOR_HEADING_MPS) & ~np.isnan(blended), blended, heading)
        moving = speed > MIN_SPEED_FOR_HEADING_MPS
        along_velocity = (x[:, IAX] * velocity[:, 0] + x[:, IAY] * velocity[:, 1]) / np.where(moving, speed, 1.0)
        accel = np.where(moving, along_velocity, 0.0)
        # A partner's own reported acceleration wins while its V2V still supports the property.
        reported = np.array([t.props.reported_accel_mps2 for t in snapshot.tracks], dtype=float)
        accel = np.where(snapshot.has_source(ACCEL, _V2V) & ~np.isnan(reported), reported, accel)
        speed_std, heading_std = _speed_and_heading_std(p[:, [IVX, IVY]][:, :, [IVX, IVY]], heading, speed)
        half_trace = 0.5 * (p[:, IX, IX] + p[:, IY, IY])
        spread = np.hypot(0.5 * (p[:, IX, IX] - p[:, IY, IY]), p[:, IX, IY])
        forward = np.array([math.cos(ego.heading_rad), math.sin(ego.heading_rad)])
        left = np.array([-forward[1], forward[0]])
        rel = position - ego.position_m
        along, across = rel @ forward, rel @ left
        self._along_ego_lane(ego, position, along, across)
        return _Kinematics(position, speed, heading, accel, speed_std, heading_std,
                           np.sqrt(np.maximum(0.0, half_trace + spread)), along, across, velocity @ forward - ego.speed_mps)

    def _along_ego_lane(self, ego: EgoPose, position_m: np.ndarray, along_m: np.ndarray, across_m: np.ndarray):
        """Station and lateral offset relative to the ego on the ego lane's centre line, where the map gives them;
        elsewhere along and across the ego heading, which on a straight road is the same thing."""
        if self._frenet_of is None:
            return
        ego_frenet = self._frenet_of(ego.x_m, ego.y_m)
        if ego_frenet is None:
            return
        for k, (x_m, y_m) in enumerate(position_m.tolist()):
            obj_frenet = self._frenet_of(x_m, y_m)
            if obj_frenet is not None:
                along_m[k], across_m[k] = obj_frenet[0] - ego_frenet[0], obj_frenet[1] - ego_frenet[1]

    def _objects(self, scene: scene_pb2.Scene, views: ObjectViews, kin: _Kinematics, lanes: list[int | None]):
        """One SceneObject per track, filled property by property: a column of numbers at a time for all objects."""
        snapshot = views.snapshot
        # Length and width are 0 where no reading ever gave one, as their confidence says.
        values = np.nan_to_num(snapshot.values)
        values[:, SPEED], values[:, HEADING], values[:, ACCEL] = kin.speed_mps, kin.heading_rad, kin.accel_mps2
        confidence, codes, valid_until = snapshot.confidence, snapshot.source_codes, snapshot.valid_until_s
        objects = self._new_objects(scene, views, kin)
        no_std = np.zeros(len(objects))
        stds = {SPEED: kin.speed_std_mps, HEADING: kin.heading_std_rad}
        for get, slot in _SCALARS:
            for obj, c, value, std, code, until in zip(objects, confidence[:, slot].tolist(), values[:, slot].tolist(),
                                                       stds.get(slot, no_std).tolist(), codes[:, slot].tolist(),
                                                       valid_until[:, slot].tolist()):
                target = get(obj)
                target.confidence = c
                if c != UNKNOWN_CONFIDENCE:
                    target.value, target.std = value, std
                    target.sources.extend(_sources_of(code))
                    target.valid_until_s = until
        position = zip(objects, confidence[:, POSITION].tolist(), kin.position_m.tolist(), kin.std_m.tolist(),
                       codes[:, POSITION].tolist(), valid_until[:, POSITION].tolist(), lanes)
        for obj, c, (x_m, y_m), std_m, code, until, lane in position:
            obj.position.confidence = c
            obj.lane_index.confidence = UNKNOWN_CONFIDENCE
            if c == UNKNOWN_CONFIDENCE:
                continue
            obj.position.x_m, obj.position.y_m, obj.position.std_m = x_m, y_m, std_m
            obj.position.sources.extend(_sources_of(code))
            obj.position.valid_until_s = until
            if lane is not None:
                obj.lane_index.value, obj.lane_index.confidence = lane, c
                obj.lane_index.sources.extend(_sources_of(code | _MAP_BIT))
                obj.lane_index.valid_until_s = until
        station = zip(objects, snapshot.tracks, confidence[:, STATION_ID].tolist(), codes[:, STATION_ID].tolist(),
                      valid_until[:, STATION_ID].tolist())
        for obj, track, c, code, until in station:
            obj.station_id.confidence = c
            if track.station_id is not None and c != UNKNOWN_CONFIDENCE:
                obj.station_id.value = track.station_id
                obj.station_id.sources.extend(_sources_of(code))
                obj.station_id.valid_until_s = until

    def _new_objects(self, scene: scene_pb2.Scene, views: ObjectViews, kin: _Kinematics) -> list:
        """The scene's objects with their plain fields: ids, class, gaps, trust, V2V time, ghost."""
        snapshot = views.snapshot
        known_class = (snapshot.confidence[:, OBJECT_CLASS] != UNKNOWN_CONFIDENCE).tolist()
        gap_m = (kin.along_m - self._front_bumper_m()).tolist()
        fields = zip(snapshot.tracks, known_class, gap_m, kin.across_m.tolist(), kin.relative_speed_mps.tolist(),
                     views.v2v_trust, views.ghost.tolist())
        add = scene.objects.add
        return [add(object_id=track.track_id, first_seen_s=track.first_seen_s,
                    object_class=track.props.object_class_value if known else 0, longitudinal_gap_m=gap,
                    lateral_offset_m=across, relative_speed_mps=relative_speed, v2v_trust=trust,
                    v2v_time_s=track.props.v2v_time_s, ghost=ghost)
                for track, known, gap, across, relative_speed, trust, ghost in fields]


def _speed_and_heading_std(velocity_cov: np.ndarray, heading_rad: np.ndarray,
                           speed_mps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Standard deviations of speed and heading (N,) from the filter's velocity covariances (N, 2, 2), to first
    order (kalman.velocity_stds). Below MIN_SPEED_FOR_HEADING_MPS the heading is that speed's worth, never more
    than pi."""
    speed_std, across_std = kalman.velocity_stds(velocity_cov, heading_rad)
    return speed_std, np.minimum(across_std / np.maximum(speed_mps, MIN_SPEED_FOR_HEADING_MPS), math.pi)
