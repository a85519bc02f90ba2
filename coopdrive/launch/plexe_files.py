"""The SUMO inputs of the Plexe baseline, written at run time: a straight one-lane road and Plexe's vehicle type.

The road is a network of one edge between two dead ends, written as SUMO writes one (no netconvert needed: the run
depends on libsumo alone). The vehicle type uses SUMO's CC car-following model (MSCFModel_CC, Plexe's), with its
first-order engine lag, acceleration limits and Ploeg's gains as XML attributes of the type.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from xml.sax.saxutils import quoteattr

# The baseline's name on the command line (coopdrive run --baseline).
SUMO_PLEXE = "sumo-plexe"
# The one edge and its route, and the vehicle type the platoon drives.
EDGE_ID = "road"
ROUTE_ID = "along"
TYPE_ID = "plexe"
# SUMO's default lane width.
LANE_WIDTH_M = 3.2


class PlexeBaselineError(ValueError):
    """A run the Plexe baseline cannot mirror, or no SUMO to run it; str() is one line naming the problem."""


@dataclass(frozen=True)
class PlexeVehicleType:
    """What SUMO's CC model is told about the platoon's vehicles (attributes of carFollowModel="CC")."""

    length_m: float
    max_accel_mps2: float
    max_decel_mps2: float
    max_speed_mps: float
    # The engine's first-order lag (tauEngine): the vehicles' driveline time constant.
    engine_tau_s: float
    # Ploeg's CACC: time gap h and gains kp, kd.
    ploeg_h_s: float
    ploeg_kp: float
    ploeg_kd: float

    def attributes(self) -> dict[str, float | str]:
        return {"carFollowModel": "CC", "length": self.length_m, "minGap": 0.0, "accel": self.max_accel_mps2,
                "decel": self.max_decel_mps2, "maxSpeed": self.max_speed_mps, "sigma": 0.0,
                "tauEngine": self.engine_tau_s, "ploegH": self.ploeg_h_s, "ploegKp": self.ploeg_kp,
                "ploegKd": self.ploeg_kd, "lanesCount": 1}


def _element(tag: str, attributes: dict) -> str:
    return f"<{tag} " + " ".join(f"{key}={quoteattr(str(value))}" for key, value in attributes.items()) + "/>"


def write_network(folder: Path, length_m: float, speed_mps: float) -> Path:
    """A straight road of one lane along x from 0 to length_m (the lane's centre half a width right of the edge's
    line, as SUMO lays a right-hand lane)."""
    centre_y = -LANE_WIDTH_M / 2.0
    lane = _element("lane", {"id": f"{EDGE_ID}_0", "index": 0, "speed": f"{speed_mps:.2f}",
                             "length": f"{length_m:.2f}", "shape": f"0.00,{centre_y:.2f} {length_m:.2f},{centre_y:.2f}"})
    start = _element("junction", {"id": "start", "type": "dead_end", "x": "0.00", "y": "0.00", "incLanes": "",
                                  "intLanes": "", "shape": f"0.00,0.00 0.00,{-LANE_WIDTH_M:.2f}"})
    end = _element("junction", {"id": "end", "type": "dead_end", "x": f"{length_m:.2f}", "y": "0.00",
                                "incLanes": f"{EDGE_ID}_0", "intLanes": "",
                                "shape": f"{length_m:.2f},{-LANE_WIDTH_M:.2f} {length_m:.2f},0.00"})
    location = _element("location", {"netOffset": "0.00,0.00", "convBoundary": f"0.00,0.00,{length_m:.2f},0.00",
                                      "origBoundary": f"0.00,0.00,{length_m:.2f},0.00", "projParameter": "!"})
    text = "\n".join(['<?xml version="1.0" encoding="UTF-8"?>', '<net version="1.20">', location,
                      f'<edge id="{EDGE_ID}" from="start" to="end" priority="1">', lane, "</edge>", start, end,
                      "</net>", ""])
    path = folder / "road.net.xml"
    path.write_text(text)
    return path


def write_routes(folder: Path, vehicle_type: PlexeVehicleType) -> Path:
    """Plexe's vehicle type and the route along the road (the vehicles are added through libsumo)."""
    text = "\n".join(["<routes>", _element("vType", {"id": TYPE_ID, **vehicle_type.attributes()}),
                      _element("route", {"id": ROUTE_ID, "edges": EDGE_ID}), "</routes>", ""])
    path = folder / "platoon.rou.xml"
    path.write_text(text)
    return path
