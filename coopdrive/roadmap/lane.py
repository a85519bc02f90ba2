"""A lane centre line as a polyline in the local ENU frame, with Frenet projection.

The polyline is stored as numpy segment arrays built once, so projecting a point is one
vectorised pass over the segments (no Python loop per segment).
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from coopdrive.roadmap.near_segments import NearSegments

# Below this squared length a segment is a duplicated vertex and is dropped.
_MIN_SEGMENT_LENGTH_M = 1e-6
# Projections a lane remembers (a few instants of every vehicle's points), then it starts again.
_RECENT_PROJECTIONS = 256


def wrap_angle_rad(angle_rad: float) -> float:
    """Wrap an angle to [-pi, pi)."""
    return (angle_rad + math.pi) % (2.0 * math.pi) - math.pi


def lateral_offset_after_m(offset_m: float, speed_mps: float, heading_error_rad: float, elapsed_s: float) -> float:
    """A lateral offset from a lane's centre moved on by elapsed_s at the given speed and heading error (a
    straight lane over so short a time): what a lane measured a moment ago says now."""
    return offset_m + speed_mps * math.sin(heading_error_rad) * elapsed_s


@dataclass(frozen=True)
class Projection:
    station_m: float
    lateral_offset_m: float
    heading_rad: float
    curvature_1pm: float
    distance_m: float


@dataclass(eq=False)
class Lane:
    """One lane: centre line in driving order, ENU metres; lateral offset is positive to the left."""

    lane_id: str
    road_id: str
    lane_index: int
    width_m: float
    points_xy: np.ndarray = field(repr=False)
    speed_limit_mps: float = 0.0
    length_m: float = field(init=False, repr=False)

    def __post_init__(self) -> None:
        points = np.asarray(self.points_xy, dtype=float).reshape(-1, 2)
        keep = np.ones(len(points), dtype=bool)
        keep[1:] = np.linalg.norm(np.diff(points, axis=0), axis=1) > _MIN_SEGMENT_LENGTH_M
        points = points[keep]
        if len(points) < 2:
            raise ValueError(f"lane {self.lane_id!r} needs at least two distinct points, got {len(points)}")
        if self.width_m <= 0.0:
            raise ValueError(f"lane {self.lane_id!r} has a non-positive width_m {self.width_m}")
        self.points_xy = points
        delta = np.diff(points, axis=0)
        self._start = points[:-1]
        self._seg_len = np.linalg.norm(delta, axis=1)
        self._unit = delta / self._seg_len[:, None]
        self._seg_heading = np.arctan2(self._unit[:, 1], self._unit[:, 0])
        self._station0 = np.concatenate(([0.0], np.cumsum(self._seg_len)[:-1]))
        self.length_m = float(self._station0[-1] + self._seg_len[-1])
        self._bbox = np.concatenate((points.min(axis=0), points.max(axis=0)))
        self._near = NearSegments(self._start, self._unit, self._seg_len)
        # The same numbers as Python floats, for projections that look at a few segments only.
        self._start_list, self._unit_list = self._start.tolist(), self._unit.tolist()
        self._seg_len_list, self._station0_list = self._seg_len.tolist(), self._station0.tolist()
        self._vertex_curvature_list = self._curvature_at_vertices().tolist()
        # The latest projections by point: one instant's position is projected again and again (by the truth,
        # the driver and each sensor in the simulator; by map matching and lane fusion in a stack).
        self._recent: dict[tuple[float, float], Projection] = {}

    def _curvature_at_vertices(self) -> np.ndarray:
        """Heading change over the mean length of the two adjacent segments, ends copied inward."""
        n_vertices = len(self.points_xy)
        curvature = np.zeros(n_vertices)
        if n_vertices > 2:
            turn = np.array([wrap_angle_rad(a) for a in np.diff(self._seg_heading)])
            curvature[1:-1] = turn / (0.5 * (self._seg_len[:-1] + self._seg_len[1:]))
            curvature[0] = curvature[1]
            curvature[-1] = curvature[-2]
        return curvature

    def near_bbox(self, x_m: float, y_m: float, margin_m: float) -> bool:
        """Cheap pre-filter before a full projection."""
        x_min, y_min, x_max, y_max = self._bbox
        return x_min - margin_m <= x_m <= x_max + margin_m and y_min - margin_m <= y_m <= y_max + margin_m

    def _segment_at(self, station_m: float) -> int:
        index = bisect.bisect_right(self._station0_list, station_m) - 1
        return min(max(index, 0), len(self._seg_len_list) - 1)

    def pose_at(self, station_m: float, lateral_offset_m: float = 0.0) -> tuple[float, float, float]:
        """Point at a station (extrapolated straight beyond the ends) and lateral offset: (x_m, y_m, heading_rad)."""
        i = self._segment_at(station_m)
        along_m = station_m - self._station0[i]
        ux, uy = self._unit[i]
        x_m = self._start[i, 0] + ux * along_m - uy * lateral_offset_m
        y_m = self._start[i, 1] + uy * along_m + ux * lateral_offset_m
        return float(x_m), float(y_m), float(self._seg_heading[i])

    def points_at(self, stations_m: np.ndarray, lateral_offset_m: float = 0.0) -> np.ndarray:
        """pose_at's points (N x 2) for many stations at once, in one vectorised pass."""
        return self.points_at_offsets(stations_m, (lateral_offset_m,))[0]

    def points_at_offsets(self, stations_m: np.ndarray, lateral_offsets_m: Sequence[float]) -> np.ndarray:
        """points_at for each of several lateral offsets (offsets x N x 2): both edges of a lane at one lookup."""
        stations_m = np.asarray(stations_m, dtype=float)
        i = np.clip(np.searchsorted(self._station0, stations_m, side="right") - 1, 0, len(self._seg_len) - 1)
        along_m = stations_m - self._station0[i]
        unit = self._unit[i]
        left = np.column_stack((-unit[:, 1], unit[:, 0]))
        offsets_m = np.asarray(lateral_offsets_m, dtype=float)[:, None, None]
        return self._start[i] + unit * along_m[:, None] + left * offsets_m

    def curvature_at(self, station_m: float) -> float:
        """Curvature interpolated between vertices, positive to the left, 1/m."""
        i = self._segment_at(station_m)
        fraction = min(max((station_m - self._station0_list[i]) / self._seg_len_list[i], 0.0), 1.0)
        return (1.0 - fraction) * self._vertex_curvature_list[i] + fraction * self._vertex_curvature_list[i + 1]

    def project_full(self, x_m: float, y_m: float) -> Projection:
        """Closest point on the centre line; stations run past the ends along the end segments."""
        key = (float(x_m), float(y_m))
        projection = self._recent.get(key)
        if projection is None:
            if len(self._recent) >= _RECENT_PROJECTIONS:
                self._recent.clear()
            projection = self._recent[key] = self._project(x_m, y_m)
        return projection

    def _project(self, x_m: float, y_m: float) -> Projection:
        candidates = self._near.candidates(x_m, y_m)
        if candidates is None:
            i, along_i, clipped_i, dist_sq_i, rx, ry = self._nearest_of_all(x_m, y_m)
        else:
            i, along_i, clipped_i, dist_sq_i, rx, ry = self._nearest_of(candidates, x_m, y_m)
        last = len(self._seg_len_list) - 1
        if (i == 0 and along_i < 0.0) or (i == last and along_i > self._seg_len_list[i]):
            along_used = along_i
        else:
            along_used = clipped_i
        ux, uy = self._unit_list[i]
        cross = ux * ry - uy * rx
        lateral_m = cross if along_used == along_i else math.copysign(math.sqrt(dist_sq_i), cross)
        station_m = self._station0_list[i] + along_used
        return Projection(
            station_m=station_m,
            lateral_offset_m=lateral_m,
            heading_rad=float(self._seg_heading[i]),
            curvature_1pm=self.curvature_at(station_m),
            distance_m=abs(lateral_m),
        )

    def _nearest_of_all(self, x_m: float, y_m: float) -> tuple[int, float, float, float, float, float]:
        """The nearest segment in one vectorised pass over all: (index, distance along it unclipped and clipped to
        it, squared distance, and the point relative to its start)."""
        rel = np.array([x_m, y_m]) - self._start
        along = np.einsum("ij,ij->i", rel, self._unit)
        clipped = np.clip(along, 0.0, self._seg_len)
        closest = self._start + self._unit * clipped[:, None]
        dist_sq = np.sum((np.array([x_m, y_m]) - closest) ** 2, axis=1)
        i = int(np.argmin(dist_sq))
        rx, ry = rel[i].tolist()
        return i, float(along[i]), float(clipped[i]), float(dist_sq[i]), rx, ry

    def _nearest_of(self, candidates: tuple[int, ...], x_m: float,
                    y_m: float) -> tuple[int, float, float, float, float, float]:
        """_nearest_of_all among the candidates only (NearSegments), the same arithmetic per segment in floats;
        the first of equals wins, as with argmin."""
        best = None
        for i in candidates:
            sx, sy = self._start_list[i]
            ux, uy = self._unit_list[i]
            rx, ry = x_m - sx, y_m - sy
            along = rx * ux + ry * uy
            clipped = min(max(along, 0.0), self._seg_len_list[i])
            dx, dy = x_m - (sx + ux * clipped), y_m - (sy + uy * clipped)
            dist_sq = dx * dx + dy * dy
            if best is None or dist_sq < best[3]:
                best = (i, along, clipped, dist_sq, rx, ry)
        return best

    def project(self, x_m: float, y_m: float) -> tuple[float, float, float, float]:
        """(station_m, lateral_offset_m, heading_rad, curvature_1pm) of the closest centre-line point."""
        p = self.project_full(x_m, y_m)
        return p.station_m, p.lateral_offset_m, p.heading_rad, p.curvature_1pm
