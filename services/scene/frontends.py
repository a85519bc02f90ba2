"""Radar, camera, sonar and V2V front ends: sensor frames -> ENU measurements with covariance.

Each front end is a small class holding its config; `measurements(...)` returns Measurement values
and skips (and counts) readings that are not numbers, so one bad track never drops a frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from coopdrive.v1 import header_pb2, sensors_pb2

from .config import CameraConfig, RadarConfig, SonarConfig, V2vConfig
from .measurement import EgoPose, Measurement, V2vObservation, cov_to_enu, polar_covs_vehicle


def _finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


# Shifted nearest points still carry this fraction of the width as lateral uncertainty (headings differ).
_SHIFTED_CENTRE_STD_FRACTION = 0.25


@dataclass
class RejectCounter:
    """Bad readings per reason, for diagnostics."""

    counts: dict[str, int] = field(default_factory=dict)

    def reject(self, reason: str) -> None:
        self.counts[reason] = self.counts.get(reason, 0) + 1


def nearest_point_to_rear_centre(x_m: float, y_m: float, width_m: float) -> tuple[np.ndarray, float]:
    """Radar and camera report the point of a vehicle nearest to them: for a vehicle beside our axis
    its near rear corner, for one across our axis the point straight ahead. Returns the rear-centre
    estimate (vehicle frame) and the lateral standard deviation left over."""
    points, lateral_std = nearest_points_to_rear_centre(np.array([x_m]), np.array([y_m]), np.array([width_m]))
    return points[0], float(lateral_std[0])


def nearest_points_to_rear_centre(x_m: np.ndarray, y_m: np.ndarray, width_m: np.ndarray) -> tuple[np.ndarray, ...]:
    """nearest_point_to_rear_centre of K reported points at once: rear centres (K, 2) and lateral stds (K,)."""
    half_width = 0.5 * width_m
    beside = np.abs(y_m) >= half_width
    centres = np.stack((x_m, np.where(beside, y_m + np.copysign(half_width, y_m), y_m)), axis=1)
    # Straddling our axis: the centre is anywhere within half a width of the reported point.
    return centres, np.where(beside, _SHIFTED_CENTRE_STD_FRACTION * width_m, half_width)


def _rear_centres(local: np.ndarray, width_m: np.ndarray, default_width_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Reported nearest points (K, 2) moved to their rear centres, and the lateral variance (K,) that leaves.
    A width of 0 was not reported: the default width stands in."""
    centres, lateral_std = nearest_points_to_rear_centre(local[:, 0], local[:, 1],
                                                         np.where(width_m != 0.0, width_m, default_width_m))
    return centres, lateral_std**2


def _valid(finite_fields: np.ndarray, range_m: np.ndarray, rejects: RejectCounter, reason: str) -> np.ndarray:
    """Rows whose fields are numbers and whose range is positive; the others are counted as rejected."""
    valid = np.isfinite(finite_fields).all(axis=1) & (range_m > 0.0)
    for _ in range(int(valid.size - np.count_nonzero(valid))):
        rejects.reject(reason)
    return valid


class RadarFrontEnd:
    def __init__(self, config: RadarConfig, rejects: RejectCounter) -> None:
        self._config = config
        self._rejects = rejects

    def measurements(self, tracks: sensors_pb2.RadarTracks, pose: EgoPose) -> list[Measurement]:
        cfg = self._config
        fields = np.array([(t.range_m, t.azimuth_rad, t.range_rate_mps, t.width_m) for t in tracks.tracks],
                          dtype=float).reshape(-1, 4)
        valid = _valid(fields[:, :3], fields[:, 0], self._rejects, "radar track not finite or non-positive range")
        ids = [t.track_id for t, ok in zip(tracks.tracks, valid.tolist(), strict=True) if ok]
        range_m, azimuth_rad, range_rate_mps, width_m = fields[valid].T
        local = range_m[:, None] * np.stack((np.cos(azimuth_rad), np.sin(azimuth_rad)), axis=1)
        cov = polar_covs_vehicle(range_m, azimuth_rad, cfg.range_std_m, cfg.bearing_std_rad)
        line_of_sight = (pose.points_to_enu(local) - pose.position_m) / range_m[:, None]
        if cfg.reports_nearest_point:
            local, lateral_var = _rear_centres(local, width_m, cfg.default_width_m)
            cov[:, 1, 1] += lateral_var
        position = pose.points_to_enu(local)
        # Range rate is relative; adding our own speed along the beam makes it absolute.
        radial = range_rate_mps + line_of_sight @ pose.velocity_mps
        cov = cov_to_enu(pose, cov)
        origin = pose.position_m
        return [
            Measurement(source=header_pb2.SENSOR_SOURCE_RADAR, time_s=pose.time_s, position_m=position[k],
                        cov_m2=cov[k], origin_m=origin, radial_speed_mps=radial[k],
                        radial_speed_std_mps=cfg.range_rate_std_mps, line_of_sight=line_of_sight[k],
                        width_m=width if width > 0.0 else None, extras={"radar_track_id": track_id})
            for k, (width, track_id) in enumerate(zip(width_m.tolist(), ids, strict=True))
        ]


@dataclass(frozen=True)
class LaneMarkings:
    """Camera lane markings passed through untouched, vehicle frame at time_s."""

    time_s: float
    markings: tuple[sensors_pb2.LaneMarking, ...]


class CameraFrontEnd:
    def __init__(self, config: CameraConfig, rejects: RejectCounter) -> None:
        self._config = config
        self._rejects = rejects

    def measurements(self, frame: sensors_pb2.CameraFrame, pose: EgoPose) -> list[Measurement]:
        cfg = self._config
        fields = np.array([(d.x_m, d.y_m, d.width_m, d.confidence) for d in frame.detections],
                          dtype=float).reshape(-1, 4)
        range_m = np.hypot(fields[:, 0], fields[:, 1])
        valid = _valid(fields[:, :2], range_m, self._rejects, "camera detection not finite or at the origin")
        classes = [d.object_class for d, ok in zip(frame.detections, valid.tolist(), strict=True) if ok]
        x_m, y_m, width_m, score = fields[valid].T
        range_m = range_m[valid]
        range_std_m = np.maximum(cfg.min_range_std_m, cfg.range_std_fraction * range_m)
        cov = polar_covs_vehicle(range_m, np.arctan2(y_m, x_m), range_std_m, cfg.bearing_std_rad)
        local = np.stack((x_m, y_m), axis=1)
        if cfg.reports_nearest_point:
            local, lateral_var = _rear_centres(local, width_m, cfg.default_width_m)
            cov[:, 1, 1] += lateral_var
        quality = np.where((0.0 < score) & (score <= 1.0), score, 1.0).tolist()
        position, cov, origin = pose.points_to_enu(local), cov_to_enu(pose, cov), pose.position_m
        return [
            Measurement(source=header_pb2.SENSOR_SOURCE_CAMERA, time_s=pose.time_s, position_m=position[k],
                        cov_m2=cov[k], origin_m=origin, width_m=width if width > 0.0 else None,
                        object_class=classes[k], quality=quality[k])
            for k, width in enumerate(width_m.tolist())
        ]

    @staticmethod
    def lane_markings(frame: sensors_pb2.CameraFrame) -> LaneMarkings:
        return LaneMarkings(time_s=frame.header.sample_time_s, markings=tuple(frame.lane_markings))


class SonarFrontEnd:
    """Echoes become near-field measurements; every sensor gives its free range."""

    def __init__(self, config: SonarConfig, rejects: RejectCounter) -> None:
        self._config = config
        self._rejects = rejects

    def measurements(self, ranges: sensors_pb2.SonarRanges, pose: EgoPose) -> list[Measurement]:
        cfg = self._config
        out = []
        for sonar in ranges.ranges:
            if not sonar.echo:
                continue
            if not _finite(sonar.range_m, sonar.mount_x_m, sonar.mount_y_m) or sonar.range_m <= 0.0:
                self._rejects.reject("sonar echo not finite or non-positive range")
                continue
            direction = np.array([math.cos(sonar.mount_yaw_rad), math.sin(sonar.mount_yaw_rad)])
            mount = np.array([sonar.mount_x_m, sonar.mount_y_m])
            local = mount + sonar.range_m * direction
            across_std = sonar.range_m * math.tan(cfg.half_beam_rad)
            normal = np.array([-direction[1], direction[0]])
            cov = cfg.range_std_m**2 * np.outer(direction, direction) + across_std**2 * np.outer(normal, normal)
            out.append(
                Measurement(
                    source=header_pb2.SENSOR_SOURCE_SONAR,
                    time_s=pose.time_s,
                    position_m=pose.to_enu(*local),
                    cov_m2=cov_to_enu(pose, cov),
                    origin_m=pose.to_enu(*mount),
                    extras={"sonar_index": sonar.sensor_index},
                )
            )
        return out

    @staticmethod
    def free_ranges_m(ranges: sensors_pb2.SonarRanges) -> list[float]:
        """Free range per sensor, in sensor_index order: up to the echo, or the full range without one."""
        ordered = sorted(ranges.ranges, key=lambda r: r.sensor_index)
        return [r.range_m if r.echo else r.max_range_m for r in ordered]


class V2vFrontEnd:
    def __init__(self, config: V2vConfig, rejects: RejectCounter) -> None:
        self._config = config
        self._rejects = rejects

    def measurement(self, obs: V2vObservation, pose: EgoPose) -> Measurement | None:
        cfg = self._config
        fields = (obs.x_m, obs.y_m, obs.speed_mps, obs.heading_rad, obs.accel_mps2, obs.sample_time_s)
        if not _finite(*fields):
            self._rejects.reject("v2v observation not finite")
            return None
        length = obs.length_m if obs.length_m > 0.0 and math.isfinite(obs.length_m) else cfg.default_length_m
        direction = np.array([math.cos(obs.heading_rad), math.sin(obs.heading_rad)])
        position = np.array([obs.x_m, obs.y_m])
        if cfg.reference_is_front:
            position = position - length * direction
        return Measurement(
            source=header_pb2.SENSOR_SOURCE_V2V,
            time_s=obs.sample_time_s,
            position_m=position,
            cov_m2=np.eye(2) * cfg.position_std_m**2,
            origin_m=pose.position_m,
            velocity_mps=obs.speed_mps * direction,
            velocity_std_mps=cfg.speed_std_mps,
            accel_mps2=obs.accel_mps2,
            heading_rad=obs.heading_rad,
            accel_std_mps2=cfg.accel_std_mps2,
            length_m=length,
            width_m=obs.width_m if obs.width_m > 0.0 else None,
            station_id=obs.station_id,
        )
