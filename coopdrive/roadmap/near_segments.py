"""NearSegments: which segments of a polyline can hold the point nearest to anything in a small square cell.

A lane's centre line has a few hundred segments, and finding the one nearest a vehicle is asked again and again
(the simulator's truths, drivers and sensors; a stack's map matching). One vectorised pass over all segments costs
a dozen numpy calls, which for 300 segments is mostly call overhead. The plane is cut into CELL_M squares; for a
cell, a segment whose distance from the cell's centre exceeds the nearest one's by more than the cell's diagonal
can hold no point nearest to any point of the cell (the triangle inequality: every point of the cell is within
half a diagonal of its centre), so only the remaining few are examined, with the same arithmetic per segment.
"""

from __future__ import annotations

import math

import numpy as np

CELL_M = 5.0
_HALF_DIAGONAL_M = CELL_M * math.sqrt(0.5)
# Rounding in the distances of the bound must not drop a segment that ties.
_BOUND_SLACK_M = 1e-6
# Beyond this many candidates (a point far from the line, where many segments are about as far) the vectorised
# pass over every segment is the cheaper.
MAX_CANDIDATES = 12
# Cells remembered, then it starts again (vehicles visit a few cells at a time).
_CELLS_KEPT = 4096


class NearSegments:
    def __init__(self, starts: np.ndarray, units: np.ndarray, lengths_m: np.ndarray) -> None:
        self._starts, self._units, self._lengths_m = starts, units, lengths_m
        self._cells: dict[tuple[int, int], tuple[int, ...] | None] = {}

    def candidates(self, x_m: float, y_m: float) -> tuple[int, ...] | None:
        """The segments (ascending) that may be nearest to (x_m, y_m); None when too many to be worth a loop."""
        cell = (math.floor(x_m / CELL_M), math.floor(y_m / CELL_M))
        found = self._cells.get(cell, False)
        if found is False:
            if len(self._cells) >= _CELLS_KEPT:
                self._cells.clear()
            found = self._cells[cell] = self._of_cell(cell)
        return found

    def _of_cell(self, cell: tuple[int, int]) -> tuple[int, ...] | None:
        centre = (np.array(cell, dtype=float) + 0.5) * CELL_M
        rel = centre - self._starts
        along = np.clip(np.einsum("ij,ij->i", rel, self._units), 0.0, self._lengths_m)
        distance_m = np.hypot(*(rel - self._units * along[:, None]).T)
        bound_m = distance_m.min() + 2.0 * _HALF_DIAGONAL_M + _BOUND_SLACK_M
        near = np.flatnonzero(distance_m <= bound_m)
        return tuple(near.tolist()) if len(near) <= MAX_CANDIDATES else None
