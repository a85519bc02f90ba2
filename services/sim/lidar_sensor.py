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
        scan = sensors_pb2.LidarScan(max_range_m=cfg.max_range_m)
        nearest_by_layer = self._nearest_hits_m(world)
        layer_ranges, layer_azimuths = [], []
        for elevation_rad, ranges in zip(cfg.layer_elevations_rad, nearest_by_layer):
            if elevation_rad < 0.0:
                ground_m = cfg.mount_height_m / math.tan(-elevation_rad)
                ranges = np.minimum(ranges, ground_m)
            ranges = self._with_clutter(ranges)
            keep = (ranges <= cfg.max_range_m) & (self.rng.random(ranges.size) >= cfg.point_dropout_probability)
            layer_ranges.append(ranges[keep] + cfg.range_sigma_m * self.rng.standard_normal(int(keep.sum())))
            layer_azimuths.append(self.beam_azimuths_rad[keep])
        # Every layer's returns from the mount to the rear axle at once: the same arithmetic on each point.
        ranges, azimuths = np.concatenate(layer_ranges), np.concatenate(layer_azimuths)
        x_m = cfg.mount_x_m + ranges * np.cos(azimuths)
        y_m = cfg.mount_y_m + ranges * np.sin(azimuths)
        bounds = np.cumsum([len(r) for r in layer_ranges])[:-1]
        layer_azimuths_rad = np.split(np.arctan2(y_m, x_m), bounds)
        layer_ranges_m = np.split(np.hypot(x_m, y_m), bounds)
        for layer_index, (elevation_rad, azimuth_rad, range_m) in enumerate(zip(
                cfg.layer_elevations_rad, layer_azimuths_rad, layer_ranges_m)):
            scan.layers.add(layer=layer_index, elevation_rad=elevation_rad, azimuth_rad=azimuth_rad.tolist(),
                            range_m=range_m.tolist())
        return scan

    def _nearest_hits_m(self, world: WorldView) -> np.ndarray:
        """Per layer (rows) and beam (columns), the range to the nearest vehicle the beam meets between the
        ground and the roof; inf where it meets none."""
        cfg = self.config
        beams = self.beam_azimuths_rad.size
        layers = len(cfg.layer_elevations_rad)
        outlines = world.outlines()
        heights = np.array([world.height_m(o) for o in world.others])
        if cfg.half_fov_rad < 0.5 * math.pi and len(outlines):
            # A forward scanner's beams meet nothing wholly behind its mount: cast at the others only (the same ranges).
            ahead = outlines.ahead_of(cfg.mount_x_m)
            outlines, heights = outlines.subset(ahead), heights[ahead]
        if not len(outlines):
            return np.full((layers, beams), np.inf)
        # (vehicle, beam): a reduction over the vehicles is then one np.minimum per vehicle, not numpy's element by
        # element pass over a short last axis.
        table = np.ascontiguousarray(
            geometry.ray_polygon_ranges((cfg.mount_x_m, cfg.mount_y_m), self.beam_azimuths_rad, outlines).T)
        slopes = np.array([math.tan(elevation_rad) for elevation_rad in cfg.layer_elevations_rad])[:, None, None]
        with np.errstate(invalid="ignore"):  # inf * 0 for a level layer is a miss either way
            beam_height = cfg.mount_height_m + table * slopes
            # A beam hits a vehicle only where it passes between the ground and the roof.
            hits = np.where((beam_height >= 0.0) & (beam_height <= heights[:, None]), table, np.inf)
        return np.minimum.reduce(hits, axis=1)
