"""A long-range radar: tracked targets in a narrow field of view with range, azimuth and range-rate noise."""
from __future__ import annotations

import math

import numpy as np

from coopdrive.services.sim import geometry
from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.services.sim.sensor_config import RadarConfig
from coopdrive.services.sim.sensor_timing import SensorTiming, stamp
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2

SENDER = "sim"


class RadarSensor:
    """Range and azimuth are in the ego frame (origin rear axle); visibility is judged from the mount."""

    def __init__(self, config: RadarConfig, rng: np.random.Generator, vehicle_id: str,
                 profile: VehicleProfile = PASSENGER_CAR) -> None:
        # Mounts left out of the configuration sit where they would on this vehicle.
        self.config = config = config.placed(profile)
        self.rng = rng
        self.vehicle_id = vehicle_id
        self.timing: SensorTiming[sensors_pb2.RadarTracks] = SensorTiming(config.timing, rng)
        self._track_ids: dict[str, int] = {}
        self._sequence = 0

    def set_dropout(self, active: bool) -> None:
        self.timing.forced_dropout = active

    def poll(self, now_s: float, world: WorldView) -> list[sensors_pb2.RadarTracks]:
        outputs = []
        for sample_s, delivery_s, message in self.timing.poll(now_s, lambda _: self._measure(world)):
            self._sequence += 1
            stamp(message.header, sample_s, delivery_s, self.vehicle_id, SENDER, self._sequence)
            outputs.append(message)
        return outputs

    def _track_id(self, vehicle_id: str) -> int:
        # Stable ids per target, as a radar's tracker keeps them while the target stays in view.
        return self._track_ids.setdefault(vehicle_id, len(self._track_ids) + 1)

    def _measure(self, world: WorldView) -> sensors_pb2.RadarTracks:
        cfg = self.config
        ego = world.ego
        mount = np.array([cfg.mount_x_m, cfg.mount_y_m])
        candidates = []
        for other, corners in zip(world.others, world.footprints_in_ego_frame()):
            point = geometry.closest_point_on_polygon(tuple(mount), corners)
            rel = point - mount
            distance_m = float(np.hypot(*rel))
            if rel[0] <= 0.0 or distance_m > cfg.max_range_m or abs(math.atan2(rel[1], rel[0])) > cfg.half_fov_rad:
                continue
            candidates.append((distance_m, other, point))
        candidates.sort(key=lambda c: c[0])
        tracks = sensors_pb2.RadarTracks()
        for distance_m, other, point in candidates[:cfg.max_tracks]:
            if self.rng.random() < cfg.miss_probability:
                continue
            range_m = float(np.hypot(*point))
            azimuth_rad = math.atan2(point[1], point[0])
            los = point / max(range_m, 1e-9)
            rel_heading = other.heading_rad - ego.heading_rad
            # Target velocity relative to the ego frame, at the reflection point (ego rotation included).
            rel_vx = other.speed_mps * math.cos(rel_heading) - ego.speed_mps + ego.yaw_rate_radps * point[1]
            rel_vy = other.speed_mps * math.sin(rel_heading) - ego.yaw_rate_radps * point[0]
            range_rate = rel_vx * los[0] + rel_vy * los[1]
            tracks.tracks.add(
                track_id=self._track_id(other.vehicle_id),
                range_m=max(range_m + cfg.range_sigma_m * self.rng.standard_normal(), 0.0),
                azimuth_rad=azimuth_rad + cfg.azimuth_sigma_rad * self.rng.standard_normal(),
                range_rate_mps=range_rate + cfg.range_rate_sigma_mps * self.rng.standard_normal(),
                accel_mps2=other.accel_mps2 * math.cos(rel_heading),
                width_m=other.width_m,
            )
        return tracks
