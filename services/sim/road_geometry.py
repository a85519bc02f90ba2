"""The road geometry the simulator needs, as a protocol the real `coopdrive.roadmap.Lane` satisfies.

`StraightLane` is a stand-in for tests and for scenarios without a map.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, Sequence, runtime_checkable

import numpy as np


@runtime_checkable
class LaneGeometry(Protocol):
    """A lane centre line in ENU metres; lateral offset positive to the left, heading ENU yaw."""

    lane_index: int
    width_m: float

    def pose_at(self, station_m: float, lateral_offset_m: float = 0.0) -> tuple[float, float, float]:
        ...

    def points_at_offsets(self, stations_m: np.ndarray, lateral_offsets_m: Sequence[float]) -> np.ndarray:
        """pose_at's points for many stations at each of several lateral offsets (offsets x N x 2)."""
        ...

    def project(self, x_m: float, y_m: float) -> tuple[float, float, float, float]:
        """(station_m, lateral_offset_m, heading_rad, curvature_1pm) of the nearest centre-line point."""
        ...


@dataclass(frozen=True)
class StraightLane:
    """A straight lane starting at (x0_m, y0_m) along heading_rad."""

    lane_index: int
    width_m: float = 3.5
    x0_m: float = 0.0
    y0_m: float = 0.0
    heading_rad: float = 0.0
    length_m: float = 10_000.0

    def pose_at(self, station_m: float, lateral_offset_m: float = 0.0) -> tuple[float, float, float]:
        cos_h, sin_h = math.cos(self.heading_rad), math.sin(self.heading_rad)
        x_m = self.x0_m + station_m * cos_h - lateral_offset_m * sin_h
        y_m = self.y0_m + station_m * sin_h + lateral_offset_m * cos_h
        return x_m, y_m, self.heading_rad

    def points_at_offsets(self, stations_m: np.ndarray, lateral_offsets_m: Sequence[float]) -> np.ndarray:
        return np.array([[self.pose_at(float(station_m), offset_m)[:2] for station_m in stations_m]
                         for offset_m in lateral_offsets_m])

    def project(self, x_m: float, y_m: float) -> tuple[float, float, float, float]:
        cos_h, sin_h = math.cos(self.heading_rad), math.sin(self.heading_rad)
        dx, dy = x_m - self.x0_m, y_m - self.y0_m
        return dx * cos_h + dy * sin_h, -dx * sin_h + dy * cos_h, self.heading_rad, 0.0


def straight_road(lane_count: int, width_m: float = 3.5, heading_rad: float = 0.0) -> list[StraightLane]:
    """Parallel straight lanes, index 0 the rightmost, each next one width_m further left."""
    lanes = []
    for index in range(lane_count):
        offset_m = index * width_m
        lanes.append(StraightLane(index, width_m, -offset_m * math.sin(heading_rad),
                                  offset_m * math.cos(heading_rad), heading_rad))
    return lanes


def nearest_lane(lanes: Sequence[LaneGeometry], x_m: float, y_m: float) -> tuple[LaneGeometry, float, float] | None:
    """The lane whose centre line is nearest, with the point's station and lateral offset on it."""
    best = None
    for lane in lanes:
        station_m, lateral_m, _, _ = lane.project(x_m, y_m)
        if best is None or abs(lateral_m) < abs(best[2]):
            best = (lane, station_m, lateral_m)
    return best


# A lane running more than this far from the vehicle's heading is another road's (intersections).
MAX_LANE_HEADING_ERROR_RAD = math.radians(60.0)


def match_lane(lanes: Sequence[LaneGeometry], x_m: float, y_m: float,
               heading_rad: float) -> tuple[LaneGeometry, float, float] | None:
    """(lane, station_m, lateral_offset_m) of the nearest lane driven in about the vehicle's direction."""
    best = None
    for lane in lanes:
        station_m, lateral_m, lane_heading, _ = lane.project(x_m, y_m)
        if abs(math.remainder(heading_rad - lane_heading, math.tau)) > MAX_LANE_HEADING_ERROR_RAD:
            continue
        if best is None or abs(lateral_m) < abs(best[2]):
            best = (lane, station_m, lateral_m)
    return best
