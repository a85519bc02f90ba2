"""What a scenario's SUMO traffic names, checked before anything starts: the configuration file and the routes files it
lists exist, and every edge their routes, trips and flows go through is an edge of the scenario's network.

Each problem is a SumoTrafficError, one line naming the file and what is wrong.
"""

from __future__ import annotations

import functools
import gzip
import importlib.util
import xml.etree.ElementTree as ElementTree
from pathlib import Path

# The elements of a routes file that name edges, and the attributes that do.
_EDGE_LISTS = ("edges", "via")
_EDGE_ENDS = ("from", "to")
_ROUTED = ("route", "vehicle", "flow", "trip")
LIBSUMO_REQUIREMENT = "libsumo>=1.28,<1.29"


class SumoTrafficError(ValueError):
    """SUMO traffic that cannot be run; str() is one line naming the file and the problem."""


def _open(path: Path):
    return gzip.open(path) if path.name.endswith(".gz") else open(path, "rb")


def _elements(path: Path, what: str):
    """Every element of an XML file, or one line saying the file is missing or not XML."""
    if not path.is_file():
        raise SumoTrafficError(f"{path}: no such SUMO {what} file")
    try:
        with _open(path) as source:
            return [element for _, element in ElementTree.iterparse(source, events=("end",))]
    except (ElementTree.ParseError, OSError, EOFError) as error:
        raise SumoTrafficError(f"{path}: not a SUMO {what} file (not XML: {' '.join(str(error).split())})") from None


def route_files_of(config_path: Path) -> list[Path]:
    """The routes files a SUMO configuration (.sumocfg) lists (its input's route-files), from its own folder."""
    values = [element.get("value", "") for element in _elements(config_path, "configuration")
              if element.tag in ("route-files", "r")]
    names = [name.strip() for value in values for name in value.split(",") if name.strip()]
    return [(config_path.parent / name).resolve() for name in names]


def routed_edges(routes_path: Path) -> set[str]:
    """Every edge id a routes file's routes, vehicles, trips and flows name."""
    edges: set[str] = set()
    for element in _elements(routes_path, "routes"):
        if element.tag not in _ROUTED:
            continue
        for attribute in _EDGE_LISTS:
            edges.update(element.get(attribute, "").split())
        edges.update(element.get(attribute) for attribute in _EDGE_ENDS if element.get(attribute))
    return edges


@functools.lru_cache(maxsize=16)
def network_edges(network_path: str) -> frozenset[str]:
    """The ids of a SUMO network's edges (its junctions' internal edges too)."""
    with _open(Path(network_path)) as source:
        return frozenset(element.get("id", "") for _, element in ElementTree.iterparse(source, events=("end",))
                         if element.tag == "edge")


def check_routes(routes_paths: list[Path], network_path: Path) -> None:
    """SumoTrafficError for a missing routes file or a route through an edge the network does not have."""
    if importlib.util.find_spec("libsumo") is None:
        raise SumoTrafficError(f"SUMO traffic needs libsumo, which is not installed (pip install '{LIBSUMO_REQUIREMENT}')")
    if not routes_paths:
        raise SumoTrafficError("no routes file: SUMO would have no vehicle to drive")
    known = network_edges(str(network_path))
    for path in routes_paths:
        unknown = sorted(routed_edges(path) - known)
        if unknown:
            shown = ", ".join(unknown[:3]) + (f" and {len(unknown) - 3} more" if len(unknown) > 3 else "")
            raise SumoTrafficError(f"{path}: a route goes through edges that {network_path.name} does not have: "
                                   f"{shown}")
