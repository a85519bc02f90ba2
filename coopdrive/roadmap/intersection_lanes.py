"""A MAPEM intersection's lanes as points in a plane about its reference point: what the planner matches the ego
to and what Foxglove draws.

ISO TS 19091 / SAE J2735 node lists: the first node lies at the stop line (the end of the lane nearest the
intersection) and is given from the reference point; each later node is given from the one before, further from
the intersection (so traffic on an ingress lane runs from the last node towards the first, and on an egress lane
from the first node away). A node-LatLon is absolute. A computed lane is its reference lane moved by an offset.
"""

from __future__ import annotations

import math

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.v1 import infrastructure_pb2 as pb

Point = tuple[float, float]


def intersection_key(reference: pb.IntersectionReference) -> tuple[int, int]:
    """(region, id); region 0 when the id is unique on its own."""
    return (reference.region if reference.HasField("region") else 0), reference.id


def leads_to_another_intersection(connection: pb.LaneConnection, key: tuple[int, int]) -> bool:
    """The connection's lane is one of another intersection's (whose MAP gives its nodes), not of `key`'s."""
    return connection.HasField("remote_intersection") and intersection_key(connection.remote_intersection) != key


def reference_plane(intersection: pb.MapIntersection) -> LocalTangentPlane | None:
    """The plane about the reference point; None when the MAP left its position unavailable."""
    if not all(map(math.isfinite, (intersection.reference_latitude_deg, intersection.reference_longitude_deg))):
        return None
    return LocalTangentPlane(intersection.reference_latitude_deg, intersection.reference_longitude_deg)


def lane_points(intersection: pb.MapIntersection, plane: LocalTangentPlane) -> dict[int, tuple[Point, ...]]:
    """Every lane's nodes as east/north points about the reference point, by lane id."""
    points: dict[int, tuple[Point, ...]] = {}
    for lane in intersection.lanes:
        if not lane.HasField("computed"):
            points[lane.lane_id] = _points(lane.nodes, plane)
    for lane in intersection.lanes:
        if lane.HasField("computed") and lane.computed.reference_lane_id in points:
            c = lane.computed
            points[lane.lane_id] = tuple((x + c.offset_east_m, y + c.offset_north_m)
                                         for x, y in points[c.reference_lane_id])
    return points


def _points(nodes, plane: LocalTangentPlane) -> tuple[Point, ...]:
    """Offsets accumulated from the reference point; an absolute node restarts the sum; a node without a position
    ends the list (the nodes after it cannot be placed)."""
    x, y, points = 0.0, 0.0, []
    for node in nodes:
        if node.HasField("latitude_deg") and node.HasField("longitude_deg"):
            x, y, _ = plane.to_enu(node.latitude_deg, node.longitude_deg)
        elif node.HasField("east_m") and node.HasField("north_m"):
            x, y = x + node.east_m, y + node.north_m
        else:
            break
        points.append((x, y))
    return tuple(points)
