"""Which ingress lane the ego drives on: the nearest centre line within the lateral tolerance whose direction of
travel is within the heading tolerance of the ego's; none rather than a guess."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .lanes import IngressLane, Point


@dataclass(frozen=True)
class LaneMatch:
    lane: IngressLane
    lateral_m: float
    # Along the lane from the ego to the stop line; negative past it, in the box.
    to_stop_line_m: float


@dataclass(frozen=True)
class MatchTolerance:
    half_width_m: float
    margin_m: float
    heading_rad: float
    box_length_m: float

    def lateral_limit_m(self, lane: IngressLane) -> float:
        return (lane.half_width_m if lane.half_width_m is not None else self.half_width_m) + self.margin_m


def match_on_lane(lane: IngressLane, position: Point, heading_rad: float, tolerance: MatchTolerance
                  ) -> LaneMatch | None:
    """The ego on this lane's centre line (its segments in the direction of travel, the one at the stop line
    carried on over the box), or None."""
    best: LaneMatch | None = None
    behind_m = 0.0  # centre line between the segment's downstream end and the stop line
    nodes = lane.nodes
    for index in range(len(nodes) - 1):
        start, end = nodes[index + 1], nodes[index]
        length_m = math.dist(start, end)
        if length_m <= 0.0:
            continue
        ux, uy = (end[0] - start[0]) / length_m, (end[1] - start[1]) / length_m
        dx, dy = position[0] - start[0], position[1] - start[1]
        along_m = dx * ux + dy * uy
        longest_m = length_m + (tolerance.box_length_m if index == 0 else 0.0)
        heading_off = abs(math.remainder(heading_rad - math.atan2(uy, ux), math.tau))
        if 0.0 <= along_m <= longest_m and heading_off <= tolerance.heading_rad:
            lateral_m = abs(dx * uy - dy * ux)
            if lateral_m <= tolerance.lateral_limit_m(lane) and (best is None or lateral_m < best.lateral_m):
                best = LaneMatch(lane, lateral_m, behind_m + length_m - along_m)
        behind_m += length_m
    return best


def nearest_match(candidates: list[LaneMatch]) -> LaneMatch | None:
    return min(candidates, key=lambda m: m.lateral_m, default=None)
