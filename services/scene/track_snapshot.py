"""The confirmed tracks at one instant as arrays, one row per track: states predicted to that instant and every
property's confidence, supporting sources and fade time, taken in one pass for the scene and its object views."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import kalman
from .support_table import SOURCE_COLUMNS, SupportTable
from .track import Track, stacked_states

# The sources of every bit code of supporting sources (bit s: source s), in enum order.
_SOURCES_OF_CODE = tuple(tuple(s for s in range(SOURCE_COLUMNS) if code >> s & 1) for code in range(1 << SOURCE_COLUMNS))


@dataclass
class TrackSnapshot:
    tracks: list[Track]
    mean: np.ndarray  # (N, 6) at time_s
    cov: np.ndarray  # (N, 6, 6)
    confidence: np.ndarray  # (N, slots), -1 where faded
    source_codes: np.ndarray  # (N, slots) bit codes of the sources supporting each property
    valid_until_s: np.ndarray  # (N, slots)
    values: np.ndarray  # (N, slots), NaN where no value was blended

    @classmethod
    def take(cls, tracks: list[Track], table: SupportTable, time_s: float, psd: float) -> TrackSnapshot:
        x, p = stacked_states(tracks) if tracks else (np.zeros((0, kalman.DIM)), np.zeros((0, kalman.DIM, kalman.DIM)))
        dt_s = time_s - np.array([t.time_s for t in tracks], dtype=float)
        x, p = kalman.predict(x, p, kalman.transition(dt_s), kalman.process_noise(dt_s, psd))
        rows = np.array([t.props.row for t in tracks], dtype=int)
        confidence, source_codes = table.confidences(rows, time_s)
        return cls(tracks, x, p, confidence, source_codes, table.valid_until_s(rows), table.values(rows))

    def has_source(self, slot: int, source: int) -> np.ndarray:
        """Whether source supports the slot's property, per track."""
        return (self.source_codes[:, slot] & (1 << source)) != 0

    def only_source(self, slot: int, source: int) -> np.ndarray:
        """Whether source alone supports the slot's property, per track."""
        return self.source_codes[:, slot] == (1 << source)

    @staticmethod
    def sources_of(code: int) -> tuple[int, ...]:
        """The sources of a bit code from source_codes, in enum order."""
        return _SOURCES_OF_CODE[code]
