"""The scene's MIO, forward MIO and lane neighbours, picked from arrays with one entry per published object.

MIO: the nearest eligible object ahead inside the ego corridor, half width lane_margin_m / 2
(Heudiasyc Fig. 4), whatever lane the map gives it, so a vehicle cutting in counts as soon as it is in
front of us. Forward MIO: the nearest eligible object ahead in the ego lane by the map (the corridor
when no map answers). Neighbours: nearest ahead and behind in the lanes either side. A car coming the other
way is never the one to follow, nor a neighbour, whichever lane band it seems to be in.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coopdrive.v1 import scene_pb2

_LANE_OFFSETS = (-1, 1)


@dataclass(frozen=True)
class Candidates:
    """Per published object: its id, gap ahead of our front bumper, lateral offset, lane relative to ours
    (+1 left), whether it may be an obstacle at all, and whether it comes the other way."""

    object_id: np.ndarray
    gap_m: np.ndarray
    lateral_offset_m: np.ndarray
    lane_offset: np.ndarray
    eligible: np.ndarray
    oncoming: np.ndarray


def pick_mio(scene: scene_pb2.Scene, objects: Candidates, corridor_half_width_m: float) -> None:
    ahead = objects.eligible & (objects.gap_m >= 0.0)
    in_corridor = ahead & (np.abs(objects.lateral_offset_m) <= corridor_half_width_m)
    if in_corridor.any():
        scene.has_mio, scene.mio_id = True, _nearest(objects, in_corridor, ahead=True)
    forward = ahead & (objects.lane_offset == 0) & ~objects.oncoming
    if forward.any():
        scene.has_forward_mio, scene.forward_mio_id = True, _nearest(objects, forward, ahead=True)


def pick_neighbours(scene: scene_pb2.Scene, objects: Candidates) -> None:
    same_way = objects.eligible & ~objects.oncoming
    for offset in _LANE_OFFSETS:
        entry = scene_pb2.LaneNeighbours(lane_offset=offset)
        in_lane = same_way & (objects.lane_offset == offset)
        ahead, behind = in_lane & (objects.gap_m >= 0.0), in_lane & (objects.gap_m < 0.0)
        if ahead.any():
            entry.has_ahead, entry.ahead_object_id = True, _nearest(objects, ahead, ahead=True)
        if behind.any():
            entry.has_behind, entry.behind_object_id = True, _nearest(objects, behind, ahead=False)
        scene.neighbours.append(entry)


def _nearest(objects: Candidates, mask: np.ndarray, ahead: bool) -> int:
    """Id of the masked object with the least gap ahead (the greatest, behind); on equal gaps the lower id
    ahead and the higher behind, as comparing (gap, id) pairs does."""
    ids, gaps = objects.object_id[mask], objects.gap_m[mask]
    order = np.lexsort((ids, gaps))
    return int(ids[order[0] if ahead else order[-1]])
