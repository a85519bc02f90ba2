"""Is a claimed spot free? Answers from the latest LiDAR beams and radar tracks.

A spot is free for the LiDAR when every beam that would hit an object there passed at least
free_margin_m beyond it; for the radar when it lies inside the radar field of view and no radar
track is at it or in front of it along the same bearing. Each answer is None when that sensor
does not cover the spot or its data is too old to say.
"""

from __future__ import annotations

import math

import numpy as np

from coopdrive.v1 import sensors_pb2

from .config import RadarConfig, TrustConfig
from .measurement import EgoPose, Measurement

# Half width of a vehicle as seen by the beams that should hit it.
_HALF_WIDTH_M = 0.9


def _wrap(angle: np.ndarray | float) -> np.ndarray | float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


class FreeSpaceOracle:
    def __init__(self, trust: TrustConfig, radar: RadarConfig) -> None:
        self._trust = trust
        self._radar = radar
        self._lidar: tuple[float, np.ndarray, np.ndarray, np.ndarray] | None = None
        self._radar_frame: tuple[EgoPose, np.ndarray] | None = None

    def set_lidar(self, scan: sensors_pb2.LidarScan, pose: EgoPose) -> None:
        angles, free = [], []
        for layer in scan.layers:
            azimuth = np.asarray(layer.azimuth_rad, dtype=float)
            ranges = np.asarray(layer.range_m, dtype=float)
            if azimuth.shape != ranges.shape:
                continue
            limit = scan.max_range_m if scan.max_range_m > 0.0 else np.inf
            no_return = ~np.isfinite(ranges) | (ranges <= 0.0) | (ranges >= limit)
            angles.append(pose.heading_rad + azimuth)
            free.append(np.where(no_return, limit, ranges * math.cos(layer.elevation_rad)))
        if angles:
            self._lidar = (pose.time_s, pose.position_m, np.concatenate(angles), np.concatenate(free))

    def set_radar(self, measurements: list[Measurement], pose: EgoPose) -> None:
        points = np.array([m.position_m for m in measurements]).reshape(-1, 2)
        self._radar_frame = (pose, points)

    def lidar_free(self, point_m: np.ndarray, time_s: float) -> bool | None:
        if self._lidar is None:
            return None
        scan_time, origin, angles, free = self._lidar
        if abs(time_s - scan_time) > self._trust.max_sensor_age_s:
            return None
        rel = point_m - origin
        distance = float(np.hypot(*rel))
        if distance <= 0.0:
            return None
        half_angle = math.atan2(_HALF_WIDTH_M, distance)
        covering = np.abs(_wrap(angles - math.atan2(rel[1], rel[0]))) <= half_angle
        if not covering.any():
            return None
        return bool(np.all(free[covering] > distance + self._trust.free_margin_m))

    def radar_free(self, point_m: np.ndarray, time_s: float) -> bool | None:
        if self._radar_frame is None:
            return None
        pose, points = self._radar_frame
        if abs(time_s - pose.time_s) > self._trust.max_sensor_age_s:
            return None
        local = pose.to_vehicle(point_m)
        distance = float(np.hypot(*local))
        bearing = math.atan2(local[1], local[0])
        if abs(bearing) > self._radar.field_of_view_rad or distance > self._radar.max_range_m:
            return None
        for seen in points:
            if np.linalg.norm(seen - point_m) <= self._trust.radar_match_m:
                return False
            seen_local = pose.to_vehicle(seen)
            seen_distance = float(np.hypot(*seen_local))
            seen_bearing = math.atan2(seen_local[1], seen_local[0])
            occludes = seen_distance < distance and abs(_wrap(seen_bearing - bearing)) <= math.atan2(
                _HALF_WIDTH_M, seen_distance
            )
            if occludes:
                return False
        return True

    def is_free(self, point_m: np.ndarray, time_s: float) -> bool:
        """True only when LiDAR and radar both cover the spot and both see it empty."""
        return bool(self.lidar_free(point_m, time_s) and self.radar_free(point_m, time_s))
