"""Is a claimed spot free? Answers from the latest LiDAR beams and radar tracks.

A spot is free for the LiDAR when it lies in the field of view and every return of the object
layers that would come from an object there lies at least free_margin_m beyond it (beams without
a return may be missing from the scan: the simulator leaves them out); for the radar when it lies inside the radar field of view and no radar
track is at it or in front of it along the same bearing. Each answer is None when that sensor
does not cover the spot or its data is too old to say.
"""

from __future__ import annotations

import math

import numpy as np

from coopdrive.v1 import sensors_pb2

from .config import LidarConfig, RadarConfig, TrustConfig
from .measurement import EgoPose, Measurement

# Half width of a vehicle as seen by the beams that should hit it.
_HALF_WIDTH_M = 0.9


def _wrap(angle: np.ndarray | float) -> np.ndarray | float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


class FreeSpaceOracle:
    def __init__(self, trust: TrustConfig, radar: RadarConfig, lidar: LidarConfig) -> None:
        self._trust = trust
        self._radar = radar
        self._lidar_config = lidar
        self._lidar: tuple[EgoPose, np.ndarray, np.ndarray] | None = None
        self._radar_frame: tuple[EgoPose, np.ndarray] | None = None

    def set_lidar(self, scan: sensors_pb2.LidarScan, pose: EgoPose) -> None:
        """Keep the object layers' returns: azimuth in the vehicle frame and how far each beam got."""
        angles, free = [], []
        limit = scan.max_range_m if scan.max_range_m > 0.0 else np.inf
        for layer in scan.layers:
            if self._lidar_config.object_layers and layer.layer not in self._lidar_config.object_layers:
                continue
            azimuth = np.asarray(layer.azimuth_rad, dtype=float)
            ranges = np.asarray(layer.range_m, dtype=float)
            if azimuth.shape != ranges.shape:
                continue
            no_return = ~np.isfinite(ranges) | (ranges <= 0.0) | (ranges >= limit)
            angles.append(azimuth)
            free.append(np.where(no_return, np.inf, ranges))
        self._lidar = (pose, np.concatenate(angles) if angles else np.zeros(0),
                       np.concatenate(free) if free else np.zeros(0))

    def set_radar(self, measurements: list[Measurement], pose: EgoPose) -> None:
        points = np.array([m.position_m for m in measurements]).reshape(-1, 2)
        self._radar_frame = (pose, points)

    def lidar_free(self, point_m: np.ndarray, time_s: float) -> bool | None:
        if self._lidar is None:
            return None
        pose, angles, free = self._lidar
        if abs(time_s - pose.time_s) > self._trust.max_sensor_age_s:
            return None
        local = pose.to_vehicle(point_m)
        distance = float(np.hypot(*local))
        bearing = math.atan2(local[1], local[0])
        if distance <= 0.0 or abs(bearing) > self._lidar_config.half_fov_rad:
            return None
        half_angle = math.atan2(_HALF_WIDTH_M, distance)
        covering = np.abs(_wrap(angles - bearing)) <= half_angle
        # Beams left out of the scan had no return: with none covering the spot, it is free too.
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
        if abs(bearing) > self._radar.half_fov_rad or distance > self._radar.max_range_m:
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
