"""Six ultrasonic sensors: the nearest echo within each beam cone, up to a few metres."""
from __future__ import annotations

import numpy as np

from coopdrive.services.sim import geometry
from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.services.sim.sensor_config import SonarConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2


class SonarSensor(TimedSensor[sensors_pb2.SonarRanges]):
    def __init__(self, config: SonarConfig, rng: np.random.Generator, vehicle_id: str,
                 profile: VehicleProfile = PASSENGER_CAR) -> None:
        # Mounts left out of the configuration sit where they would on this vehicle.
        self.config = config = config.placed(profile)
        super().__init__(config.timing, rng, vehicle_id)
        cone_rad = np.linspace(-config.half_beam_rad, config.half_beam_rad, config.rays_per_beam)
        # Every mount's cone of rays, cast together: rays (mount, ray) flattened, each from its own mount.
        self._ray_origins = np.array([(mount.x_m, mount.y_m) for mount in config.mounts for _ in cone_rad],
                                     dtype=float).reshape(-1, 2)
        self._ray_azimuths_rad = np.concatenate([mount.yaw_rad + cone_rad for mount in config.mounts]) \
            if config.mounts else np.empty(0)
        self._farthest_mount_m = float(np.hypot(self._ray_origins[:, 0], self._ray_origins[:, 1]).max()) \
            if config.mounts else 0.0

    def poll(self, now_s: float, world: WorldView) -> list[sensors_pb2.SonarRanges]:
        return self._deliver(now_s, lambda: self._measure(world))

    def _measure(self, world: WorldView) -> sensors_pb2.SonarRanges:
        cfg = self.config
        outlines = world.outlines()
        message = sensors_pb2.SonarRanges()
        if not cfg.mounts:
            return message
        # An echo comes from a few metres at most: the rays are cast only at the vehicles near enough (the same ranges).
        near = outlines.near((0.0, 0.0), self._farthest_mount_m + cfg.max_range_m)
        all_ranges, _ = geometry.cast_rays(self._ray_origins, self._ray_azimuths_rad, near, cfg.max_range_m)
        for index, (mount, ranges) in enumerate(zip(cfg.mounts, all_ranges.reshape(len(cfg.mounts), -1))):
            nearest_m = float(ranges.min()) if ranges.size else np.inf
            echo = bool(np.isfinite(nearest_m))
            range_m = min(max(nearest_m + cfg.range_sigma_m * self.rng.standard_normal(), 0.0), cfg.max_range_m) \
                if echo else cfg.max_range_m
            message.ranges.add(sensor_index=index, mount_x_m=mount.x_m, mount_y_m=mount.y_m,
                               mount_yaw_rad=mount.yaw_rad, range_m=range_m, max_range_m=cfg.max_range_m, echo=echo)
        return message
