"""The MAPEM of a simulated signalised intersection, from its configuration and the road map.

Each approach gives two lanes: its ingress lane, whose node list starts at the stop line and runs back up the
approach (ISO TS 19091 / SAE J2735: an ingress lane's first node is its stop line), and its egress lane, from where
the lane leaves the box on out. The first node is an offset from the intersection's reference point, each next one
from the node before (NodeXY of TS 103 301), east and north metres. The ingress lane connects to its egress lane
under the approach's signal group.
"""
from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

from coopdrive.services.sim.intersection_config import SignalApproach, SignalisedIntersection
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.v1 import infrastructure_pb2 as pb

# Nodes every 50 m at most: a curved lane keeps its shape (a chord of 50 m on a 200 m radius sags 1.6 m), and each
# offset fits a 28-bit node.
NODE_SPACING_M = 50.0

LanesOfRoad = Callable[[str], Sequence[LaneGeometry]]
ToGeodetic = Callable[[float, float], tuple[float, float, float]]


def approach_lane(lanes_of_road: LanesOfRoad, approach: SignalApproach) -> LaneGeometry:
    """The map lane of an approach; ValueError naming it when the map has none."""
    for lane in lanes_of_road(approach.road):
        if lane.lane_index == approach.lane:
            return lane
    raise ValueError(f"signal approach: the map has no lane {approach.lane} on road {approach.road!r}")


def _stations(start_m: float, end_m: float) -> list[float]:
    """From start_m to end_m (either way) at NODE_SPACING_M at most; both ends included."""
    count = max(1, math.ceil(abs(end_m - start_m) / NODE_SPACING_M - 1e-9))
    return [float(s) for s in np.linspace(start_m, end_m, count + 1)]


def _nodes(lane: LaneGeometry, stations_m: list[float], reference_xy: tuple[float, float]) -> list[pb.LaneNode]:
    nodes = []
    previous_x, previous_y = reference_xy
    for station_m in stations_m:
        x_m, y_m, _ = lane.pose_at(station_m, 0.0)
        nodes.append(pb.LaneNode(east_m=round(x_m - previous_x, 2), north_m=round(y_m - previous_y, 2)))
        # The next offset is from where this node is on the wire (centimetres), so rounding does not add up.
        previous_x, previous_y = previous_x + nodes[-1].east_m, previous_y + nodes[-1].north_m
    return nodes


def intersection_map(config: SignalisedIntersection, lanes_of_road: LanesOfRoad, to_geodetic: ToGeodetic,
                     misplaced_m: tuple[float, float] = (0.0, 0.0)) -> pb.MapIntersection:
    """misplaced_m: (east, north) the reference point is stated off where it is, every lane with it (a fault)."""
    east_m, north_m = misplaced_m
    latitude_deg, longitude_deg, _ = to_geodetic(config.x_m + east_m, config.y_m + north_m)
    intersection = pb.MapIntersection(revision=config.revision, name=config.name,
                                      reference_latitude_deg=latitude_deg, reference_longitude_deg=longitude_deg)
    intersection.id.id = config.intersection_id
    if config.region is not None:
        intersection.id.region = config.region
    reference = (config.x_m, config.y_m)
    widths = set()
    for number, approach in enumerate(config.approaches, start=1):
        lane = approach_lane(lanes_of_road, approach)
        widths.add(lane.width_m)
        stop_m = approach.stop_station_m
        ingress = intersection.lanes.add(lane_id=approach.ingress_lane_id, ingress_approach=number,
                                         ingress_path=True, lane_type=pb.LANE_TYPE_VEHICLE)
        ingress.nodes.extend(_nodes(lane, _stations(stop_m, max(stop_m - approach.approach_length_m, 0.0)),
                                    reference))
        ingress.connections.add(to_lane_id=approach.egress_lane_id, signal_group=approach.signal_group)
        exit_m = stop_m + approach.box_length_m
        # No egressApproach: the lane leaves on the far arm, which this configuration does not name.
        egress = intersection.lanes.add(lane_id=approach.egress_lane_id, egress_path=True,
                                        lane_type=pb.LANE_TYPE_VEHICLE)
        egress.nodes.extend(_nodes(lane, _stations(exit_m, exit_m + approach.exit_length_m), reference))
    if len(widths) == 1:
        intersection.lane_width_m = widths.pop()
    intersection.signal_groups.extend(sorted({a.signal_group for a in config.approaches}))
    return intersection
