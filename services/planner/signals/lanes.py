"""A MAPEM intersection's ingress lanes in a plane about its reference point (coopdrive/roadmap/intersection_lanes.py),
each with its stop line and the signal group of each movement it connects to."""

from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap.intersection_lanes import Point, intersection_key, lane_points, leads_to_another_intersection
from coopdrive.v1 import infrastructure_pb2 as pb

from ..config import Intention

# A movement turning less than this from the ingress direction goes straight on; more (up to U_TURN_DEG) turns.
STRAIGHT_DEG = 45.0
U_TURN_DEG = 150.0


@dataclass(frozen=True)
class Movement:
    to_lane_id: int
    signal_group: int | None
    # Towards where it leaves, counter-clockwise from east (None: the egress lane is not in this MAP).
    exit_heading_rad: float | None


@dataclass(frozen=True)
class IngressLane:
    intersection: tuple[int, int]
    lane_id: int
    # East/north metres about the intersection's reference point, the stop line first.
    nodes: tuple[Point, ...]
    half_width_m: float | None
    movements: tuple[Movement, ...]

    @property
    def stop_line(self) -> Point:
        return self.nodes[0]

    @property
    def length_m(self) -> float:
        return sum(math.dist(a, b) for a, b in zip(self.nodes, self.nodes[1:]))

    @property
    def signalised(self) -> bool:
        return any(m.signal_group is not None for m in self.movements)

    def heading_at_stop_line_rad(self) -> float:
        (x0, y0), (x1, y1) = self.nodes[0], self.nodes[1]
        return math.atan2(y0 - y1, x0 - x1)

    def signal_group(self, intention: Intention) -> int | None:
        """The signal group of the movement the intention takes; None when no movement of this lane is that
        turn, or two are with different groups (no guessing)."""
        groups = {m.signal_group for m in self.movements if m.exit_heading_rad is not None
                  and turn_of(self.heading_at_stop_line_rad(), m.exit_heading_rad) is intention}
        return groups.pop() if len(groups) == 1 else None


def turn_of(entry_rad: float, exit_rad: float) -> Intention | None:
    """Straight, left (counter-clockwise) or right; None for a U-turn."""
    turn_deg = math.degrees(math.remainder(exit_rad - entry_rad, math.tau))
    if abs(turn_deg) <= STRAIGHT_DEG:
        return Intention.STRAIGHT
    if abs(turn_deg) >= U_TURN_DEG:
        return None
    return Intention.LEFT if turn_deg > 0 else Intention.RIGHT


def ingress_lanes(intersection: pb.MapIntersection, plane: LocalTangentPlane) -> list[IngressLane]:
    """The vehicle ingress lanes with at least two nodes whose positions the MAP gives."""
    nodes = lane_points(intersection, plane)
    half_width_m = intersection.lane_width_m / 2.0 if intersection.HasField("lane_width_m") else None
    key = intersection_key(intersection.id)
    lanes = []
    for lane in intersection.lanes:
        points = nodes.get(lane.lane_id, ())
        if lane.ingress_path and lane.lane_type == pb.LANE_TYPE_VEHICLE and len(points) >= 2:
            movements = tuple(_movement(c, nodes, key) for c in lane.connections)
            lanes.append(IngressLane(key, lane.lane_id, points, half_width_m, movements))
    return lanes


def _movement(connection: pb.LaneConnection, nodes: dict[int, tuple[Point, ...]], key: tuple[int, int]) -> Movement:
    group = connection.signal_group if connection.HasField("signal_group") else None
    exit_nodes = () if leads_to_another_intersection(connection, key) else nodes.get(connection.to_lane_id, ())
    heading = None
    if len(exit_nodes) >= 2:
        (x0, y0), (x1, y1) = exit_nodes[0], exit_nodes[1]
        heading = math.atan2(y1 - y0, x1 - x0)
    return Movement(connection.to_lane_id, group, heading)
