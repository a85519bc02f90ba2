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
from .measurement import EgoPose, Measurement, V2vObservation, cov_to_enu, polar_cov_vehicle


def _finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


# Shifted nearest points still carry this fraction of the width as lateral uncertainty (headings differ).
_SHIFTED_CENTRE_STD_FRACTION = 0.25


def nearest_point_to_rear_centre(x_m: float, y_m: float, width_m: float) -> tuple[np.ndarray, float]:
    """Radar and camera report the point of a vehicle nearest to them: for a vehicle beside our axis
    its near rear corner, for one across our axis the point straight ahead. Returns the rear-centre
    estimate (vehicle frame) and the lateral standard deviation left over."""
    half_width = 0.5 * width_m
    if abs(y_m) >= half_width:
        return np.array([x_m, y_m + math.copysign(half_width, y_m)]), _SHIFTED_CENTRE_STD_FRACTION * width_m
    # Straddling our axis: the centre is anywhere within half a width of the reported point.
    return np.array([x_m, y_m]), half_width


@dataclass
class RejectCounter:
    """Bad readings per reason, for diagnostics."""

    counts: dict[str, int] = field(default_factory=dict)

    def reject(self, reason: str) -> None:
        self.counts[reason] = self.counts.get(reason, 0) + 1


class RadarFrontEnd:
    def __init__(self, config: RadarConfig, rejects: RejectCounter) -> None:
        self._config = config
        self._rejects = rejects

    def measurements(self, tracks: sensors_pb2.RadarTracks, pose: EgoPose) -> list[Measurement]:
        cfg = self._config
        out = []
        for track in tracks.tracks:
            if not _finite(track.range_m, track.azimuth_rad, track.range_rate_mps) or track.range_m <= 0.0:
                self._rejects.reject("radar track not finite or non-positive range")
                continue
            local = track.range_m * np.array([math.cos(track.azimuth_rad), math.sin(track.azimuth_rad)])
            cov = polar_cov_vehicle(track.range_m, track.azimuth_rad, cfg.range_std_m, cfg.bearing_std_rad)
            line_of_sight = (pose.to_enu(*local) - pose.position_m) / track.range_m
            if cfg.reports_nearest_point:
                local, lateral_std = nearest_point_to_rear_centre(*local, track.width_m or cfg.default_width_m)
                cov[1, 1] += lateral_std**2
            position = pose.to_enu(*local)
            # Range rate is relative; adding our own speed along the beam makes it absolute.
            radial = track.range_rate_mps + float(pose.velocity_mps @ line_of_sight)
            out.append(
                Measurement(
                    source=header_pb2.SENSOR_SOURCE_RADAR,
                    time_s=pose.time_s,
                    position_m=position,
                    cov_m2=cov_to_enu(pose, cov),
                    origin_m=pose.position_m,
                    radial_speed_mps=radial,
                    radial_speed_std_mps=cfg.range_rate_std_mps,
                    line_of_sight=line_of_sight,
                    width_m=track.width_m if track.width_m > 0.0 else None,
                    extras={"radar_track_id": track.track_id},
                )
            )
        return out


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
        out = []
        for det in frame.detections:
            range_m = math.hypot(det.x_m, det.y_m)
            if not _finite(det.x_m, det.y_m) or range_m <= 0.0:
                self._rejects.reject("camera detection not finite or at the origin")
                continue
            bearing = math.atan2(det.y_m, det.x_m)
            range_std = max(cfg.min_range_std_m, cfg.range_std_fraction * range_m)
            cov = polar_cov_vehicle(range_m, bearing, range_std, cfg.bearing_std_rad)
            local = np.array([det.x_m, det.y_m])
            if cfg.reports_nearest_point:
                local, lateral_std = nearest_point_to_rear_centre(det.x_m, det.y_m, det.width_m or cfg.default_width_m)
                cov[1, 1] += lateral_std**2
            quality = det.confidence if 0.0 < det.confidence <= 1.0 else 1.0
            out.append(
                Measurement(
                    source=header_pb2.SENSOR_SOURCE_CAMERA,
                    time_s=pose.time_s,
                    position_m=pose.to_enu(*local),
                    cov_m2=cov_to_enu(pose, cov),
                    origin_m=pose.position_m,
                    width_m=det.width_m if det.width_m > 0.0 else None,
                    object_class=det.object_class,
                    quality=quality,
                )
            )
        return out

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
