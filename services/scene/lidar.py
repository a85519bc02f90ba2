"""LiDAR front end: Heudiasyc geometric clustering per layer, then one measurement per object.

Two consecutive points (in azimuth order) belong to the same cluster when they are closer than
max_gap_m; clusters with fewer than min_points are noise or fragments (Heudiasyc Sect. 3.2, Fig. 12),
and are taken out before the rest is split again, so a stray echo cannot cut a vehicle in two.
The layers see the same vehicle at slightly different heights, so surviving clusters of different
layers that touch are merged before they become measurements.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coopdrive.v1 import header_pb2, sensors_pb2

from .config import LidarConfig
from .measurement import EgoPose, Measurement, cov_to_enu, polar_cov_vehicle

# A vehicle's rear face may be partly hidden, so its measured centre is off by up to a tenth of its width.
_FACE_CENTRE_STD_FRACTION = 0.1
# A centre placed half a typical width out from a vehicle's near side is off by however much wider or narrower the
# vehicle is than typical: cars are 1.6-2.0 m wide, trucks 2.5 m.
_NEAR_SIDE_CENTRE_STD_FRACTION = 0.25


@dataclass
class LidarCluster:
    """A cluster in the vehicle frame: its points and axis-aligned box."""

    layers: tuple[int, ...]
    points_m: np.ndarray  # (n, 2) vehicle frame

    @property
    def x_min_m(self) -> float:
        return float(self.points_m[:, 0].min())

    @property
    def x_max_m(self) -> float:
        return float(self.points_m[:, 0].max())

    @property
    def y_min_m(self) -> float:
        return float(self.points_m[:, 1].min())

    @property
    def y_max_m(self) -> float:
        return float(self.points_m[:, 1].max())

    @property
    def width_m(self) -> float:
        return self.y_max_m - self.y_min_m

    @property
    def extent_m(self) -> float:
        return max(self.x_max_m - self.x_min_m, self.width_m)

    @property
    def rear_centre_m(self) -> np.ndarray:
        """The face nearest to us: the rear bumper of a vehicle ahead."""
        return np.array([self.x_min_m, 0.5 * (self.y_min_m + self.y_max_m)])

    def box_gap_m(self, other: LidarCluster) -> float:
        dx = max(0.0, max(self.x_min_m, other.x_min_m) - min(self.x_max_m, other.x_max_m))
        dy = max(0.0, max(self.y_min_m, other.y_min_m) - min(self.y_max_m, other.y_max_m))
        return math.hypot(dx, dy)


def expected_points(width_m: float, distance_m: float, resolution_rad: float) -> float:
    """Beams hitting the back of a vehicle: n = w / (d* tan phi)."""
    return width_m / (distance_m * math.tan(resolution_rad))  # (eq. 1) Heudiasyc


def max_detection_range_m(width_m: float, min_points: int, resolution_rad: float) -> float:
    """Eq. (1) inverted: beyond this a vehicle returns fewer than min_points and is dropped."""
    return width_m / (min_points * math.tan(resolution_rad))  # (eq. 1) Heudiasyc, inverted


def _across_beam(bearing_rad: float) -> np.ndarray:
    """Projector onto the direction across the beam, vehicle frame."""
    normal = np.array([-math.sin(bearing_rad), math.cos(bearing_rad)])
    return np.outer(normal, normal)


def layer_points(layer: sensors_pb2.LidarLayer, max_range_m: float) -> np.ndarray:
    """Valid returns of one layer in the vehicle frame, in azimuth order. range_m is taken as the
    horizontal range, as the simulator reports it; at LiDAR elevations of a degree or two the
    difference from the slant range is under a millimetre per metre anyway."""
    azimuth = np.asarray(layer.azimuth_rad, dtype=float)
    ranges = np.asarray(layer.range_m, dtype=float)
    if azimuth.shape != ranges.shape:
        raise ValueError(f"lidar layer {layer.layer}: {azimuth.size} azimuths but {ranges.size} ranges")
    limit = max_range_m if max_range_m > 0.0 else np.inf
    valid = np.isfinite(ranges) & np.isfinite(azimuth) & (ranges > 0.0) & (ranges < limit)
    order = np.argsort(azimuth[valid], kind="stable")
    horizontal = ranges[valid][order]
    angle = azimuth[valid][order]
    return np.column_stack((horizontal * np.cos(angle), horizontal * np.sin(angle)))


def split_consecutive(points_m: np.ndarray, max_gap_m: float) -> list[np.ndarray]:
    """Runs of consecutive points whose neighbour distance stays within max_gap_m."""
    if len(points_m) == 0:
        return []
    gaps = np.linalg.norm(np.diff(points_m, axis=0), axis=1)
    cuts = np.flatnonzero(gaps > max_gap_m) + 1
    return np.split(points_m, cuts)


def object_runs(points_m: np.ndarray, max_gap_m: float, min_points: int) -> list[np.ndarray]:
    """Runs of at least min_points points, after the stray ones are taken out.

    A beam echoing off spray between us and a car returns a lone point in front of its rear face, which
    cuts the face in two: two half-width clusters, one of which starts a second, phantom track beside the
    car. Runs too short to be an object are therefore removed first and the rest split again, so the
    face's two halves, whose neighbours are within max_gap_m once the stray point is gone, join up."""
    kept = [run for run in split_consecutive(points_m, max_gap_m) if len(run) >= min_points]
    if len(kept) < 2:
        return kept
    # Splitting again only joins kept runs (within each the gaps stay short), so every run is still long enough.
    return split_consecutive(np.vstack(kept), max_gap_m)


class LidarClusterer:
    """Scan -> clusters -> ENU measurements."""

    def __init__(self, config: LidarConfig, front_bumper_x_m: float = 0.0) -> None:
        self._config = config
        self._mount_x_m = config.mount_x_m if config.mount_x_m is not None else front_bumper_x_m

    def clusters(self, scan: sensors_pb2.LidarScan) -> list[LidarCluster]:
        cfg = self._config
        per_layer: list[LidarCluster] = []
        for layer in scan.layers:
            if cfg.object_layers and layer.layer not in cfg.object_layers:
                continue
            for run in object_runs(layer_points(layer, scan.max_range_m), cfg.max_gap_m, cfg.min_points):
                per_layer.append(LidarCluster(layers=(layer.layer,), points_m=run))
        merged = self._merge_layers(per_layer)
        return [c for c in merged if c.extent_m <= cfg.max_extent_m and self._near_road(c)]

    def measurements(self, scan: sensors_pb2.LidarScan, pose: EgoPose) -> list[Measurement]:
        cfg = self._config
        out = []
        for cluster in self.clusters(scan):
            cut_by_fov = self._cut_by_field_of_view(cluster)
            rear, face_std_m = self._rear_centre(cluster, cut_by_fov)
            range_m = float(np.hypot(*rear))
            bearing = math.atan2(rear[1], rear[0])
            cov = polar_cov_vehicle(range_m, bearing, cfg.range_std_m, cfg.bearing_std_rad)
            cov += face_std_m**2 * _across_beam(bearing)
            if cut_by_fov:
                # Only the lateral position is known: the first visible point slides with us as the flank
                # passes, so where the vehicle's rear is says nothing about how it moves.
                cov[0, 0] += cfg.typical_length_m**2
            out.append(
                Measurement(
                    source=header_pb2.SENSOR_SOURCE_LIDAR,
                    time_s=pose.time_s,
                    position_m=pose.to_enu(*rear),
                    cov_m2=cov_to_enu(pose, cov),
                    origin_m=pose.position_m,
                    width_m=cluster.width_m,
                    extras={"points": len(cluster.points_m)},
                    ambiguous=cut_by_fov,
                )
            )
        return out

    def _rear_centre(self, cluster: LidarCluster, cut_by_fov: bool) -> tuple[np.ndarray, float]:
        """The rear centre a cluster gives (vehicle frame) and the standard deviation of its centre across the beam.

        A face narrower than a vehicle is partly hidden: its true centre may lie anywhere within the missing
        width. Where the edge of the field of view cuts a vehicle wholly to one side of us, what is hidden is its
        outer part, and the visible edge nearest our axis is its near side: the centre is half a vehicle's width
        further out. (Taking the middle of what is left put a car passing the other way, as the field of view
        cut it down to its flank, a metre into our lane within 0.2 s: a new track read that as a car turning
        across our path, and the intersection's safety circle braked for it.)"""
        cfg = self._config
        missing_m = max(0.0, cfg.typical_width_m - cluster.width_m)
        one_side = cluster.y_min_m > 0.0 or cluster.y_max_m < 0.0
        if cut_by_fov and one_side and missing_m > 0.0:
            near_side_m = cluster.y_min_m if cluster.y_min_m > 0.0 else cluster.y_max_m
            centre_m = near_side_m + math.copysign(0.5 * cfg.typical_width_m, near_side_m)
            return np.array([cluster.x_min_m, centre_m]), _NEAR_SIDE_CENTRE_STD_FRACTION * cfg.typical_width_m
        return cluster.rear_centre_m, max(_FACE_CENTRE_STD_FRACTION * cluster.width_m, 0.5 * missing_m)

    def _cut_by_field_of_view(self, cluster: LidarCluster) -> bool:
        bearings = np.arctan2(cluster.points_m[:, 1], cluster.points_m[:, 0] - self._mount_x_m)
        return float(np.abs(bearings).max()) >= self._config.half_fov_rad - self._config.fov_edge_margin_rad

    def _near_road(self, cluster: LidarCluster) -> bool:
        return cluster.x_max_m > 0.0 and abs(cluster.rear_centre_m[1]) <= self._config.max_lateral_m

    def _merge_layers(self, clusters: list[LidarCluster]) -> list[LidarCluster]:
        merged: list[LidarCluster] = []
        for cluster in clusters:
            joined = cluster
            keep = []
            for other in merged:
                # Clusters of one layer were already split on purpose; only other layers may join.
                shares_layer = bool(set(joined.layers) & set(other.layers))
                if not shares_layer and joined.box_gap_m(other) <= self._config.max_gap_m:
                    joined = LidarCluster(
                        layers=tuple(sorted(set(joined.layers) | set(other.layers))),
                        points_m=np.vstack((other.points_m, joined.points_m)),
                    )
                else:
                    keep.append(other)
            keep.append(joined)
            merged = keep
        return merged
