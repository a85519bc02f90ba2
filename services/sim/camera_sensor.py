"""A front camera: detected vehicles (unoccluded, in view; some missed, some misclassified, widths noisy) and
the ego lane's markings from the map."""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from coopdrive.services.sim import geometry
from coopdrive.services.sim.road_geometry import LaneGeometry, match_lane
from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.services.sim.sensor_config import CameraConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2

LANE_SAMPLES = 12
CUBIC = 3
# Detection confidence falls linearly from 1 at the camera to this value at max range.
FAR_CONFIDENCE = 0.5
# What a misclassified detection may be taken for.
CLASSES = (sensors_pb2.OBJECT_CLASS_CAR, sensors_pb2.OBJECT_CLASS_TRUCK, sensors_pb2.OBJECT_CLASS_EMERGENCY_VEHICLE,
           sensors_pb2.OBJECT_CLASS_OBSTACLE)
MIN_WIDTH_M = 0.3


class CameraSensor(TimedSensor[sensors_pb2.CameraFrame]):
    def __init__(self, config: CameraConfig, rng: np.random.Generator, vehicle_id: str,
                 lanes: Sequence[LaneGeometry] = (), profile: VehicleProfile = PASSENGER_CAR) -> None:
        # Mounts left out of the configuration sit where they would on this vehicle.
        self.config = config = config.placed(profile)
        self.lanes = list(lanes)
        super().__init__(config.timing, rng, vehicle_id)
        self._detection_ids: dict[str, int] = {}

    def detected_ids(self) -> set[str]:
        """The vehicles the camera has detected so far in the run."""
        return set(self._detection_ids)

    def poll(self, now_s: float, world: WorldView) -> list[sensors_pb2.CameraFrame]:
        return self._deliver(now_s, lambda: self._measure(world))

    def _measure(self, world: WorldView) -> sensors_pb2.CameraFrame:
        frame = sensors_pb2.CameraFrame()
        self._detect(world, frame)
        self._lane_markings(world, frame)
        return frame

    def _detect(self, world: WorldView, frame: sensors_pb2.CameraFrame) -> None:
        cfg = self.config
        mount = np.array([cfg.mount_x_m, cfg.mount_y_m])
        outlines = world.outlines()
        if not len(outlines):
            return
        points = outlines.closest_points(tuple(mount))
        rel = points - mount
        distances_m = np.hypot(rel[:, 0], rel[:, 1])
        centres = outlines.corners.mean(axis=1) - mount
        in_view = []
        for index, ((rel_x, rel_y), distance_m, (centre_x, centre_y)) in enumerate(zip(
                rel.tolist(), distances_m.tolist(), centres.tolist())):
            if rel_x <= 0.0 or distance_m > cfg.max_range_m:
                continue
            bearing_rad = math.atan2(rel_y, rel_x)
            if abs(bearing_rad) <= cfg.half_fov_rad:
                in_view.append((index, distance_m, (math.atan2(centre_y, centre_x), bearing_rad)))
        if not in_view:
            return
        # Seen only if a ray to its centre or to its nearest point meets it first: all the rays cast at once.
        _, hit = geometry.cast_rays(tuple(mount), np.array([rays for *_, rays in in_view]).ravel(), outlines,
                                    cfg.max_range_m)
        for (index, distance_m, _), first_hits in zip(in_view, hit.reshape(-1, 2).tolist()):
            if index not in first_hits or self.rng.random() < cfg.miss_probability:
                continue
            other = world.others[index]
            x_m, y_m = self._noisy(rel[index]) + mount
            frame.detections.add(
                detection_id=self._detection_ids.setdefault(other.vehicle_id, len(self._detection_ids) + 1),
                object_class=self._classify(world.object_class(other)), x_m=x_m, y_m=y_m,
                width_m=self._width_m(other.width_m),
                confidence=1.0 - (1.0 - FAR_CONFIDENCE) * distance_m / cfg.max_range_m,
            )

    def _noisy(self, from_mount_m: np.ndarray) -> np.ndarray:
        """A point seen from the camera, its range and bearing each off by the camera's errors."""
        cfg = self.config
        range_m = float(np.hypot(*from_mount_m))
        range_sigma_m = max(cfg.min_range_sigma_m, cfg.range_sigma_per_m2 * range_m**2)
        range_noise_m, bearing_noise_rad = self.rng.standard_normal(2) * (range_sigma_m, cfg.bearing_sigma_rad)
        bearing_rad = math.atan2(from_mount_m[1], from_mount_m[0]) + bearing_noise_rad
        return (range_m + range_noise_m) * np.array([math.cos(bearing_rad), math.sin(bearing_rad)])

    def _classify(self, true_class: int) -> int:
        probability = self.config.misclassification_probability
        if probability <= 0.0 or self.rng.random() >= probability:
            return true_class
        return int(self.rng.choice([c for c in CLASSES if c != true_class]))

    def _width_m(self, true_width_m: float) -> float:
        sigma_m = self.config.width_sigma_m
        return max(true_width_m + sigma_m * self.rng.standard_normal(), MIN_WIDTH_M) if sigma_m > 0 else true_width_m

    def _lane_markings(self, world: WorldView, frame: sensors_pb2.CameraFrame) -> None:
        if not self.lanes:
            return
        cfg = self.config
        ego = world.ego
        found = match_lane(self.lanes, ego.x_m, ego.y_m, ego.heading_rad)
        if found is None:
            return
        lane, station_m, _ = found
        stations = station_m + cfg.mount_x_m + np.linspace(0.0, cfg.lane_view_range_m, LANE_SAMPLES)
        offset_noise_m = cfg.lane_offset_sigma_m * self.rng.standard_normal(2)
        heading_noise = cfg.lane_heading_sigma_rad * self.rng.standard_normal()
        half_width_m = lane.width_m / 2.0
        edges = lane.points_at_offsets(stations, (half_width_m, -half_width_m))
        local = geometry.to_ego_frame(edges.reshape(-1, 2), ego.x_m, ego.y_m, ego.heading_rad).reshape(edges.shape)
        for side, points, noise_m in zip((sensors_pb2.LANE_SIDE_LEFT, sensors_pb2.LANE_SIDE_RIGHT), local,
                                         offset_noise_m):
            c3, c2, c1, c0 = np.polyfit(points[:, 0], points[:, 1], CUBIC)
            frame.lane_markings.add(side=side, c0_m=c0 + noise_m, c1=c1 + heading_noise, c2_1pm=c2, c3_1pm2=c3,
                                    view_range_m=cfg.lane_view_range_m, quality=1.0)
