"""A multi-layer scanning LiDAR: per layer, the nearest return of each beam on vehicles or the ground, some
beams lost (dropouts) and some echoing off rain or spray (clutter)."""
from __future__ import annotations

import math

import numpy as np

from coopdrive.services.sim import geometry
from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.services.sim.sensor_config import LidarConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2


class LidarSensor(TimedSensor[sensors_pb2.LidarScan]):
    """Beams leave the mount; returns are reported as horizontal range and azimuth from the rear axle
    (ego frame), nearer vehicles occluding farther ones, a beam passing over a vehicle flying on."""

    def __init__(self, config: LidarConfig, rng: np.random.Generator, vehicle_id: str,
                 profile: VehicleProfile = PASSENGER_CAR) -> None:
        # Mounts left out of the configuration sit where they would on this vehicle.
        self.config = config = config.placed(profile)
        super().__init__(config.timing, rng, vehicle_id)
        steps = int(round(2.0 * config.half_fov_rad / config.azimuth_resolution_rad))
        self.beam_azimuths_rad = np.linspace(-config.half_fov_rad, config.half_fov_rad, steps + 1)
        # Fault hook (lidar_clutter): the fraction of cluttered beams instead of the configured one.
        self.clutter_probability: float | None = None

    def set_clutter(self, clutter_probability: float | None) -> None:
        """Fault hook (lidar_clutter): this fraction of beams echoes off spray; None goes back to the configured one."""
        self.clutter_probability = clutter_probability

    def poll(self, now_s: float, world: WorldView) -> list[sensors_pb2.LidarScan]:
        return self._deliver(now_s, lambda: self._measure(world))

    def _with_clutter(self, ranges: np.ndarray) -> np.ndarray:
        """Beams that echo off rain, spray or dust somewhere short of what they would have hit."""
        probability = self.config.clutter_probability if self.clutter_probability is None else self.clutter_probability
        if probability <= 0.0:
            return ranges
        cluttered = self.rng.random(ranges.size) < probability
        reach_m = np.minimum(ranges, self.config.max_range_m)
        return np.where(cluttered, self.rng.random(ranges.size) * reach_m, ranges)

    def _measure(self, world: WorldView) -> sensors_pb2.LidarScan:
        cfg = self.config
        mount = (cfg.mount_x_m, cfg.mount_y_m)
        outlines = world.outlines()
        heights = np.array([world.height_m(o) for o in world.others])
        table = geometry.ray_polygon_ranges(mount, self.beam_azimuths_rad, outlines) if len(outlines) else \
            np.full((self.beam_azimuths_rad.size, 0), np.inf)
        scan = sensors_pb2.LidarScan(max_range_m=cfg.max_range_m)
        for layer_index, elevation_rad in enumerate(cfg.layer_elevations_rad):
            with np.errstate(invalid="ignore"):  # inf * 0 for the level layer is a miss either way
                beam_height = cfg.mount_height_m + table * math.tan(elevation_rad)
                # A beam hits a vehicle only where it passes between the ground and the roof.
                hits = np.where((beam_height >= 0.0) & (beam_height <= heights[None, :]), table, np.inf)
            ranges = hits.min(axis=1) if hits.shape[1] else np.full(self.beam_azimuths_rad.size, np.inf)
            if elevation_rad < 0.0:
                ground_m = cfg.mount_height_m / math.tan(-elevation_rad)
                ranges = np.minimum(ranges, ground_m)
            ranges = self._with_clutter(ranges)
            keep = (ranges <= cfg.max_range_m) & (self.rng.random(ranges.size) >= cfg.point_dropout_probability)
            ranges = ranges[keep] + cfg.range_sigma_m * self.rng.standard_normal(int(keep.sum()))
            azimuths = self.beam_azimuths_rad[keep]
            x_m = cfg.mount_x_m + ranges * np.cos(azimuths)
            y_m = cfg.mount_y_m + ranges * np.sin(azimuths)
            scan.layers.add(layer=layer_index, elevation_rad=elevation_rad,
                            azimuth_rad=np.arctan2(y_m, x_m).tolist(), range_m=np.hypot(x_m, y_m).tolist())
        return scan
