"""One lane of a SUMO network as sumolib reads it, before it becomes a Lane of our road map."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SumoLane:
    """A lane of a normal edge in SUMO's own terms: network coordinates (x, y metres), SUMO's index counting every
    lane of the edge from the right (sidewalks and bike lanes too), and whether a passenger car may use it."""

    lane_id: str
    edge_id: str
    sumo_index: int
    shape_xy: tuple[tuple[float, float], ...]
    width_m: float
    speed_limit_mps: float
    drivable: bool
    # The lanes a vehicle may go on to from this one's end, through the junction (SUMO's connections).
    successor_ids: tuple[str, ...] = ()
