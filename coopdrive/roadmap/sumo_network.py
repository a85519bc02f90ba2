"""SUMO road networks (.net.xml, as netconvert and netgenerate write them) as lane maps, read through sumolib:
what RoadMap.load makes a map of, when it is given a SUMO network.

Every lane of a normal edge that a passenger car may use becomes a Lane: the edge id is its road id, SUMO's lane id
its lane id, and its lane_index counts the edge's drivable lanes from the right (SUMO's own index counts sidewalks
and bike lanes too); shape, width and speed limit are SUMO's. Junctions' internal lanes are left out; SUMO's
connections between kept lanes become the map's successors.

A geo-referenced network (its location element has a projParameter, as netconvert writes from OpenStreetMap) is
unprojected point by point (sumolib's net.convertXY2LonLat) and laid in the ENU frame about the geodetic point of
its boundary's centre, so GNSS fixes, CAM positions and Foxglove are in real latitude and longitude. A network
without a projection (netgenerate's) is taken as ENU metres about the default origin (coopdrive.geodesy).
"""

from __future__ import annotations

import functools
import gzip
import xml.etree.ElementTree as ElementTree
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pymap3d

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.roadmap.lane import Lane
from coopdrive.roadmap.sumo_lane import SumoLane

# A map named by a file with one of these endings is a SUMO network, any other a GeoJSON map or a shipped map's name.
SUMO_MAP_SUFFIXES = (".xml", ".xml.gz")
NETWORK_SUFFIXES = (".net.xml", ".net.xml.gz", ".xml", ".xml.gz")
# SUMO's vehicle class of the cars our stacks drive: a lane that does not allow it is not ours to drive on.
DRIVING_CLASS = "passenger"
SUMOLIB_REQUIREMENT = "sumolib>=1.28,<1.29"
PYPROJ_REQUIREMENT = "pyproj>=3.6"

# (x, y) arrays in network coordinates -> (lon, lat) arrays in degrees.
ToLonLat = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]
# A road map's parts: its ENU origin (lat_deg, lon_deg, alt_m), lanes, and each lane's successors by lane id.
MapParts = tuple[tuple[float, float, float], list[Lane], dict[str, tuple[str, ...]]]


class SumoNetworkError(ValueError):
    """A SUMO network that cannot be a map; str() is one line naming the file and the problem."""


class SumoNetworkMissing(SumoNetworkError, FileNotFoundError):
    """No file where the SUMO network was named: an OSError too, as a missing GeoJSON map's is, so that what reports a
    map file it cannot open (replaying a recording on another machine) reports this one alike."""


def names_sumo_network(map_name: str) -> bool:
    """Whether a scenario's `map` names a SUMO network file (rather than a GeoJSON file or a shipped map)."""
    return str(map_name).endswith(SUMO_MAP_SUFFIXES)


def read_sumo_network(path: str | Path) -> MapParts:
    """The road map's parts of a SUMO network file; SumoNetworkError (one line) for a missing file, a file that is not a
    SUMO network, a network without drivable lanes, or sumolib (or pyproj, for a projected network) not installed."""
    path = Path(path)
    if not path.is_file():
        raise SumoNetworkMissing(f"{path}: no such SUMO network file")
    root = _root_element(path)
    if root != "net":
        raise SumoNetworkError(f"{path}: not a SUMO network (its root element is <{root}>, not <net>)")
    try:
        import sumolib
    except ImportError:
        raise SumoNetworkError(f"{path}: reading a SUMO network needs sumolib, which is not installed "
                               f"(pip install '{SUMOLIB_REQUIREMENT}')") from None
    try:
        net = sumolib.net.readNet(str(path), withInternal=False, withPrograms=False, withFoes=False)
    except Exception as error:  # sumolib raises what its XML parser or its own checks raise
        raise SumoNetworkError(f"{path}: not a readable SUMO network: {' '.join(str(error).split())}") from None
    lanes = [_lane_of(lane, edge.getID()) for edge in net.getEdges(withInternal=False) if edge.getFunction() == ""
             for lane in edge.getLanes()]
    x_min, y_min, x_max, y_max = net.getBoundary()
    centre_xy = (0.5 * (x_min + x_max), 0.5 * (y_min + y_max))
    return map_parts_of(lanes, _projection_of(net, path), centre_xy, source=str(path))


def check_sumo_network(path: str | Path) -> None:
    """read_sumo_network's SumoNetworkError, if any, without keeping the map: a file already read whole in this
    process is not read again while unchanged (a run's launcher loads its scenario file several times, and a city's
    network takes seconds)."""
    path = Path(path)
    stat = path.stat() if path.is_file() else None
    _read_once(str(path), stat.st_mtime_ns if stat else 0, stat.st_size if stat else 0)


@functools.lru_cache(maxsize=16)
def _read_once(path: str, mtime_ns: int, size: int) -> None:
    """Cached by the file's path, time and size; an error is not cached, so a bad file is read again each time."""
    read_sumo_network(path)


def map_parts_of(lanes: Sequence[SumoLane], to_lon_lat: ToLonLat | None, centre_xy: tuple[float, float],
                 source: str = "<network>") -> MapParts:
    """The road map's parts of a network's lanes: the drivable ones, numbered from the right on each edge, in the ENU
    frame about the geodetic point of centre_xy (to_lon_lat given), or with network coordinates as ENU metres about
    the default origin (no projection)."""
    drivable = [lane for lane in lanes if lane.drivable]
    if not drivable:
        kinds = "no lanes at all" if not lanes else f"{len(lanes)} lanes, none that a {DRIVING_CLASS} car may use"
        raise SumoNetworkError(f"{source}: the SUMO network has no drivable lane ({kinds})")
    if to_lon_lat is None:
        origin = GeodeticOrigin().as_tuple()
        to_enu = _as_enu
    else:
        lon, lat = to_lon_lat(np.array([centre_xy[0]]), np.array([centre_xy[1]]))
        origin = (float(lat[0]), float(lon[0]), 0.0)
        to_enu = _unprojected(to_lon_lat, origin)
    ours = [_our_lane(lane, index, to_enu(np.array(lane.shape_xy, dtype=float)))
            for lane, index in _indexed_from_the_right(drivable)]
    kept = {lane.lane_id for lane in drivable}
    successors = {lane.lane_id: tuple(s for s in lane.successor_ids if s in kept) for lane in drivable}
    return origin, ours, successors


def _indexed_from_the_right(lanes: Sequence[SumoLane]) -> list[tuple[SumoLane, int]]:
    """Each lane with its index among its edge's drivable lanes, 0 the rightmost."""
    by_edge: dict[str, list[SumoLane]] = {}
    for lane in lanes:
        by_edge.setdefault(lane.edge_id, []).append(lane)
    return [(lane, index) for edge_lanes in by_edge.values()
            for index, lane in enumerate(sorted(edge_lanes, key=lambda lane: lane.sumo_index))]


def _our_lane(lane: SumoLane, lane_index: int, points_xy: np.ndarray) -> Lane:
    return Lane(lane_id=lane.lane_id, road_id=lane.edge_id, lane_index=lane_index, width_m=lane.width_m,
                points_xy=points_xy, speed_limit_mps=lane.speed_limit_mps)


def _as_enu(points_xy: np.ndarray) -> np.ndarray:
    return points_xy


def _unprojected(to_lon_lat: ToLonLat, origin: tuple[float, float, float]) -> Callable[[np.ndarray], np.ndarray]:
    def to_enu(points_xy: np.ndarray) -> np.ndarray:
        lon, lat = to_lon_lat(points_xy[:, 0].copy(), points_xy[:, 1].copy())
        east, north, _ = pymap3d.geodetic2enu(np.asarray(lat), np.asarray(lon), np.zeros(len(points_xy)), *origin)
        return np.column_stack((np.atleast_1d(east), np.atleast_1d(north)))
    return to_enu


def _lane_of(lane, edge_id: str) -> SumoLane:
    """Our record of a sumolib lane."""
    return SumoLane(lane_id=lane.getID(), edge_id=edge_id, sumo_index=lane.getIndex(),
                    shape_xy=tuple((float(x), float(y)) for x, y, *_ in lane.getShape()),
                    width_m=float(lane.getWidth()), speed_limit_mps=float(lane.getSpeed()),
                    drivable=bool(lane.allows(DRIVING_CLASS)),
                    successor_ids=tuple(c.getToLane().getID() for c in lane.getOutgoing()))


def _projection_of(net, path: Path) -> ToLonLat | None:
    if not net.hasGeoProj():
        return None
    try:
        import pyproj  # noqa: F401  (sumolib's convertXY2LonLat projects through it)
    except ImportError:
        raise SumoNetworkError(f"{path}: the network's projection needs pyproj, which is not installed "
                               f"(pip install '{PYPROJ_REQUIREMENT}')") from None
    try:
        net.getGeoProj()
    except Exception as error:  # pyproj's CRSError, or sumolib's RuntimeError
        raise SumoNetworkError(f"{path}: the network's projection is not one PROJ knows: "
                               f"{' '.join(str(error).split())}") from None
    return net.convertXY2LonLat


def _root_element(path: Path) -> str:
    """The tag of the file's root element, or a SumoNetworkError for a file that is not XML."""
    try:
        with (gzip.open(path) if path.name.endswith(".gz") else open(path, "rb")) as source:
            for _, element in ElementTree.iterparse(source, events=("start",)):
                return element.tag
    except (ElementTree.ParseError, OSError, EOFError) as error:
        raise SumoNetworkError(f"{path}: not a SUMO network (not XML: {' '.join(str(error).split())})") from None
    raise SumoNetworkError(f"{path}: not a SUMO network (an empty file)")


def sumo_map_name(path: str | Path) -> str:
    """A network's map name: its file's name without the ending (a network from grid.net.xml is "grid")."""
    name = Path(path).name
    for suffix in NETWORK_SUFFIXES:
        if name.endswith(suffix):
            return name[: -len(suffix)]
    return name
