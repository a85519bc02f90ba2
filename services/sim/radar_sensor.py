"""A long-range radar: tracked targets in a narrow field of view with range, azimuth and range-rate noise and
bias, missed targets, false tracks, unresolved neighbours merged into one track, and track ids that switch."""
from __future__ import annotations

import math

import numpy as np

from coopdrive.services.sim.profiles import PASSENGER_CAR, VehicleProfile
from coopdrive.services.sim.sensor_config import RadarConfig
from coopdrive.services.sim.timed_sensor import TimedSensor
from coopdrive.services.sim.world_view import WorldView
from coopdrive.v1 import sensors_pb2

# A width estimate never falls below this (a radar sees at least a reflector's extent).
MIN_RADAR_WIDTH_M = 0.5
# False tracks are reported from here out to the maximum range.
MIN_FALSE_ALARM_RANGE_M = 5.0


class RadarSensor(TimedSensor[sensors_pb2.RadarTracks]):
    """Range and azimuth are in the ego frame (origin rear axle); visibility is judged from the mount."""

    def __init__(self, config: RadarConfig, rng: np.random.Generator, vehicle_id: str,
                 profile: VehicleProfile = PASSENGER_CAR) -> None:
        # Mounts left out of the configuration sit where they would on this vehicle.
        self.config = config = config.placed(profile)
        super().__init__(config.timing, rng, vehicle_id)
        self._track_ids: dict[str, int] = {}
        self._next_track_id = 1
        # Fault hook (radar_clutter): false tracks per scan instead of the configured rate.
        self.clutter_per_scan: float | None = None

    def set_clutter(self, false_alarms_per_scan: float | None) -> None:
        """Fault hook (radar_clutter): this many false tracks per scan; None goes back to the configured rate."""
        self.clutter_per_scan = false_alarms_per_scan

    def poll(self, now_s: float, world: WorldView) -> list[sensors_pb2.RadarTracks]:
        return self._deliver(now_s, lambda: self._measure(world))

    def tracked_ids(self) -> set[str]:
        """The vehicles the radar has tracked so far in the run."""
        return set(self._track_ids)

    def _new_track_id(self) -> int:
        self._next_track_id += 1
        return self._next_track_id - 1

    def _track_id(self, vehicle_id: str) -> int:
        # Ids per target as the radar's tracker keeps them, now and then lost and started afresh.
        p_switch = self.config.track_id_switch_probability
        if vehicle_id not in self._track_ids or (p_switch > 0.0 and self.rng.random() < p_switch):
            self._track_ids[vehicle_id] = self._new_track_id()
        return self._track_ids[vehicle_id]

    def _resolved(self, candidates: list) -> list:
        """The candidates (nearest first) without those the radar cannot tell from a nearer one."""
        cfg = self.config
        kept: list = []
        for candidate in candidates:
            point = candidate[2]
            range_m, azimuth = float(np.hypot(*point)), math.atan2(point[1], point[0])
            if not any(abs(range_m - r) < cfg.range_resolution_m and abs(azimuth - a) < cfg.azimuth_resolution_rad
                       for r, a in (k[3] for k in kept)):
                kept.append((*candidate, (range_m, azimuth)))
        return kept

    def _measure(self, world: WorldView) -> sensors_pb2.RadarTracks:
        cfg = self.config
        ego = world.ego
        mount = np.array([cfg.mount_x_m, cfg.mount_y_m])
        candidates = []
        outlines = world.outlines()
        for other, point in zip(world.others, outlines.closest_points(tuple(mount))):
            rel = point - mount
            distance_m = float(np.hypot(*rel))
            if rel[0] <= 0.0 or distance_m > cfg.max_range_m or abs(math.atan2(rel[1], rel[0])) > cfg.half_fov_rad:
                continue
            candidates.append((distance_m, other, point))
        candidates.sort(key=lambda c: c[0])
        tracks = sensors_pb2.RadarTracks()
        for distance_m, other, point, (range_m, azimuth_rad) in self._resolved(candidates)[:cfg.max_tracks]:
            if self.rng.random() < cfg.miss_probability:
                continue
            los = point / max(range_m, 1e-9)
            rel_heading = other.heading_rad - ego.heading_rad
            # Target velocity relative to the ego frame, at the reflection point (ego rotation included).
            rel_vx = other.speed_mps * math.cos(rel_heading) - ego.speed_mps + ego.yaw_rate_radps * point[1]
            rel_vy = other.speed_mps * math.sin(rel_heading) - ego.yaw_rate_radps * point[0]
            range_rate = rel_vx * los[0] + rel_vy * los[1]
            tracks.tracks.add(
                track_id=self._track_id(other.vehicle_id),
                range_m=max(range_m + cfg.range_bias_m + cfg.range_sigma_m * self.rng.standard_normal(), 0.0),
                azimuth_rad=azimuth_rad + cfg.azimuth_bias_rad + cfg.azimuth_sigma_rad * self.rng.standard_normal(),
                range_rate_mps=range_rate + cfg.range_rate_sigma_mps * self.rng.standard_normal(),
                accel_mps2=other.accel_mps2 * math.cos(rel_heading),
                width_m=self._width_m(other.width_m),
            )
        self._add_false_alarms(tracks, ego.speed_mps)
        return tracks

    def _width_m(self, true_width_m: float) -> float:
        sigma_m = self.config.width_sigma_m
        if sigma_m <= 0.0:
            return true_width_m
        return max(true_width_m + sigma_m * self.rng.standard_normal(), MIN_RADAR_WIDTH_M)

    def _add_false_alarms(self, tracks: sensors_pb2.RadarTracks, ego_speed_mps: float) -> None:
        """Stationary reflectors the radar takes for targets for one scan."""
        cfg = self.config
        rate = cfg.false_alarms_per_scan if self.clutter_per_scan is None else self.clutter_per_scan
        if rate <= 0.0:
            return
        for _ in range(int(self.rng.poisson(rate))):
            range_m = self.rng.uniform(MIN_FALSE_ALARM_RANGE_M, cfg.max_range_m)
            azimuth_rad = self.rng.uniform(-cfg.half_fov_rad, cfg.half_fov_rad)
            tracks.tracks.add(track_id=self._new_track_id(), range_m=range_m, azimuth_rad=azimuth_rad,
                              range_rate_mps=-ego_speed_mps * math.cos(azimuth_rad), accel_mps2=0.0,
                              width_m=MIN_RADAR_WIDTH_M)
