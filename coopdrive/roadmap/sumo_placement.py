"""A vehicle placed as SUMO places one: on an edge's lane at a position (metres from the lane's start, SUMO's `pos`),
turned into our road map's station on that lane.

SUMO measures a position along its lane's length, which on a geo-referenced network is the projected length (and may
be set apart from the shape's); our lane is the same shape unprojected onto the ground. So the position is put on
SUMO's shape first (as SUMO does: scaled by the shape's length over the lane's), then laid in our frame (SumoFrame)
and projected onto our lane: a vehicle stands where SUMO would stand it, within the projection's centimetres.
"""

from __future__ import annotations

import functools
from pathlib import Path

from coopdrive.roadmap.road_map import RoadMap
from coopdrive.roadmap.sumo_frame import SumoFrame
from coopdrive.roadmap.sumo_network import SumoNetworkError


class SumoPlacementError(ValueError):
    """A SUMO edge, lane or position that is not on the network; str() is one line."""


def station_on_sumo_lane(network_path: str | Path, edge_id: str, lane_index: int, pos_m: float) -> float:
    """Our station (metres along our lane) of SUMO's position pos_m on the edge's lane_index-th drivable lane from
    the right (the scenario file's `lane`); SumoPlacementError for an unknown edge or lane, or a position off it."""
    path = Path(network_path)
    stat = path.stat()
    road_map, net = _network(str(path), stat.st_mtime_ns, stat.st_size)
    if not net.hasEdge(edge_id) or net.getEdge(edge_id).getFunction() != "":
        raise SumoPlacementError(f"edge {edge_id!r}: {path.name} has no such edge")
    ours = road_map.lanes_of_road(edge_id)
    lane = next((lane for lane in ours if lane.lane_index == lane_index), None)
    if lane is None:
        raise SumoPlacementError(f"edge {edge_id!r} has no lane {lane_index} (it has {len(ours)} lanes a car may use)")
    sumo_lane = net.getLane(lane.lane_id)
    length_m = sumo_lane.getLength()
    if not 0.0 <= pos_m <= length_m:
        raise SumoPlacementError(f"pos_m {pos_m:g} is off edge {edge_id!r} (its lane {lane_index} is "
                                 f"{length_m:.2f} m long)")
    import sumolib

    shape = sumo_lane.getShape()
    on_shape_m = pos_m * sumolib.geomhelper.polyLength(shape) / length_m if length_m > 0.0 else 0.0
    x_m, y_m = sumolib.geomhelper.positionAtShapeOffset(shape, on_shape_m)[:2]
    frame = SumoFrame(road_map, net if net.hasGeoProj() else None)
    return float(lane.project(*frame.to_local(x_m, y_m))[0])


@functools.lru_cache(maxsize=4)
def _network(path: str, mtime_ns: int, size: int):
    """The road map of a network file and sumolib's network, read once while the file is unchanged (a scenario is
    loaded several times in a run's launch)."""
    import sumolib

    try:
        net = sumolib.net.readNet(path, withInternal=False, withPrograms=False, withFoes=False)
    except Exception as error:  # what sumolib's parser raises; the map's own check has said it already
        raise SumoNetworkError(f"{path}: not a readable SUMO network: {' '.join(str(error).split())}") from None
    return RoadMap.load(path), net
