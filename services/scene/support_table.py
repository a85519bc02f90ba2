"""Per-property confidence after the Chalmers scene service (Svensson 2017, Sect. 3.5 and 4.3.1), for many
properties of many objects at once.

The thesis gives the rules in words; the equations below are our formalisation of them:

  (C1) support of source s decays between readings:  c_s(t) = c_s(t_s) * exp(-decay_s * (t - t_s)),
       and is gone once t - t_s > fade_s ("objects and surfaces have a fade time").
  (C2) a reading of match quality q in [0, 1] moves it towards q * max_s:
       c_s <- c_s(t) + gain_s * (q * max_s - c_s(t))
       ("a new matching reading increases the confidence ... according to sensor types and how well
       the properties of the objects matches up"); readings that match poorly, or come from a V2V
       station we trust little, cannot push one source beyond q * max_s.
  (C3) independent sources combine as c = 1 - prod_s (1 - c_s(t)), so a second sensor seeing the same
       thing is a boost ("detection of the same object by a new sensor gives a confidence boost").
  (C4) values blend as v <- (c_old v_old + b c_new v_new) / (c_old + b c_new), b the bias for new data,
       multiplied by closer_bias when a distance-like value gets smaller ("a bias for closer readings").

With every source faded the confidence is -1 and the value is withheld.

The table holds one row per object, one slot per property of it and one column per sensor source (the
header_pb2.SensorSource value), so a frame's readings and a scene's confidences are a few array operations for
every object together instead of a few Python calls per property of each.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from .config import SourceConfig
from coopdrive.messages.unknowns import UNKNOWN_CONFIDENCE

# Columns: header_pb2.SensorSource values, UNSPECIFIED (0) to MAP (6); a source without settings is never used.
SOURCE_COLUMNS = 7
# Up to this many rows, one entry at a time in plain floats costs less than setting up arrays.
ONE_BY_ONE_MAX = 4
_INITIAL_ROWS = 16
# Bit s of a code of supporting sources: source s.
_BITS = 1 << np.arange(SOURCE_COLUMNS)


class SupportTable:
    def __init__(self, source_config: Callable[[int], SourceConfig], slots: int, new_data_bias: float = 3.0,
                 closer_bias: Sequence[float] | None = None) -> None:
        """closer_bias: per slot (default 1, none); source_config(source) gives a source's settings, looked up the
        first time it supports anything."""
        self._source_config = source_config
        self._new_data_bias = new_data_bias
        self._closer_bias = np.ones(slots) if closer_bias is None else np.asarray(closer_bias, dtype=float)
        self._fade_s = np.zeros(SOURCE_COLUMNS)
        self._decay_per_s = np.zeros(SOURCE_COLUMNS)
        self._max = np.zeros(SOURCE_COLUMNS)
        self._gain = np.zeros(SOURCE_COLUMNS)
        # The same settings as plain floats, (fade_s, decay_per_s, max, gain) by source, for the one-entry paths:
        # arithmetic on numpy scalars costs several times Python's on floats, for the same IEEE results.
        self._settings_one: dict[int, tuple[float, float, float, float]] = {}
        # The columns of the sources that have given support (their settings looked up) in enum order, and the span
        # from the first to the last of them. The other columns hold no support, and numpy reduces a short last axis
        # element by element (a max over 7 columns of 200 x 8 slots cost 90 us), so the reductions over sources
        # leave them out.
        self._columns: list[int] = []
        self._span = slice(0, 0)
        self._conf = np.zeros((_INITIAL_ROWS, slots, SOURCE_COLUMNS))
        # -inf: never supported, so its support has always faded and counts for no valid_until_s.
        self._time_s = np.full((_INITIAL_ROWS, slots, SOURCE_COLUMNS), -math.inf)
        self._value = np.full((_INITIAL_ROWS, slots), math.nan)
        self._free = list(range(_INITIAL_ROWS - 1, -1, -1))

    # -- rows ------------------------------------------------------------------------------

    def allocate(self) -> int:
        """A fresh row: no support and no value in any slot."""
        if not self._free:
            grown = len(self._conf)
            self._conf = np.concatenate((self._conf, np.zeros_like(self._conf)))
            self._time_s = np.concatenate((self._time_s, np.full_like(self._time_s, -math.inf)))
            self._value = np.concatenate((self._value, np.full_like(self._value, math.nan)))
            self._free = list(range(2 * grown - 1, grown - 1, -1))
        row = self._free.pop()
        self._conf[row], self._time_s[row], self._value[row] = 0.0, -math.inf, math.nan
        return row

    def release(self, row: int) -> None:
        self._free.append(row)

    # -- reading ---------------------------------------------------------------------------

    def confidences(self, rows, time_s) -> tuple[np.ndarray, np.ndarray]:
        """Fused confidence (C3) of every slot of the rows, -1 where every source has faded: (rows, slots); and
        which sources still support each slot as a bit code (bit s: source s): (rows, slots)."""
        time_s = np.asarray(time_s, dtype=float)
        return self._fused(self._conf[rows], self._time_s[rows], time_s[:, None] if time_s.ndim else time_s)

    def slot_confidences(self, rows, slot: int, time_s) -> tuple[np.ndarray, np.ndarray]:
        """confidences() of one slot: (rows,) and (rows,)."""
        time_s = np.asarray(time_s, dtype=float)
        return self._fused(self._conf[rows, slot], self._time_s[rows, slot], time_s)

    def faded(self, rows: list[int], slot: int, time_s: float) -> list[bool]:
        """Whether every source of the slot has faded, per row; a few rows one by one, where that is cheaper."""
        if len(rows) <= ONE_BY_ONE_MAX:
            return [self.confidence_one(row, slot, time_s)[0] == UNKNOWN_CONFIDENCE for row in rows]
        return (self.slot_confidences(rows, slot, time_s)[0] == UNKNOWN_CONFIDENCE).tolist()

    def valid_until_s(self, rows) -> np.ndarray:
        """When the last supporting source of each slot fades, -inf where none ever did: (rows, slots)."""
        return self._latest_support_s(rows, self._fade_s)

    def last_support_s(self, rows) -> np.ndarray:
        return self._latest_support_s(rows)

    def _latest_support_s(self, rows, fade_s: np.ndarray | None = None) -> np.ndarray:
        """The latest support time over the sources that gave any (plus each source's fade_s), -inf where none did:
        (rows, slots). One np.maximum per such column: see _columns."""
        support_time_s = self._time_s[rows]
        latest = np.full(support_time_s.shape[:-1], -math.inf)
        for column in self._columns:
            times_s = support_time_s[..., column]
            np.maximum(latest, times_s if fade_s is None else times_s + fade_s[column], out=latest)
        return latest

    def values(self, rows) -> np.ndarray:
        """Blended values (C4), NaN where none was given: (rows, slots)."""
        return self._value[rows]

    # -- readings --------------------------------------------------------------------------

    def support(self, rows, slots, source: int, time_s, quality) -> None:
        """One reading by source of the given slots of each row (C2). quality in [0, 1]: one per row (N,), one per
        row and slot (N, len(slots)), or one for all; time_s one per row or one for all."""
        rows, slots = _block(rows, slots)
        self._credit(source, rows, slots, _per_row(time_s), _per_row(quality))

    def update(self, rows, slots, source: int, time_s, value, quality) -> None:
        """Support plus value blending (C4), for properties no filter estimates: value and quality shaped as
        support()'s quality; a NaN value is no reading of that slot."""
        rows, slots = _block(rows, slots)
        time_s, value, quality = _per_row(time_s), _per_row(value), _per_row(quality)
        old_confidence = self._fused(self._conf[rows, slots], self._time_s[rows, slots], time_s)[0]
        old_confidence = np.maximum(0.0, old_confidence)
        old_value = self._value[rows, slots]
        bias = self._new_data_bias * np.where(value < old_value, self._closer_bias[slots], 1.0)
        new_weight = bias * self._max[self._column(source)] * np.maximum(quality, 1e-3)
        blended = (old_confidence * old_value + new_weight * value) / (old_confidence + new_weight)
        fresh = np.isnan(old_value) | (old_confidence == 0.0)
        given = ~np.isnan(value)
        self._value[rows, slots] = np.where(given, np.where(fresh, value, blended), old_value)
        self._credit(source, rows, slots, time_s, np.where(given, quality, 0.0))

    def _credit(self, source: int, rows: np.ndarray, slots: np.ndarray, time_s, quality) -> None:
        """(C2) for a block of rows (N, 1) and slots (1, S). A late reading never moves the support time
        backwards, and does not decay into the future; one that matches not at all supports nothing and must not
        keep the property alive."""
        column = self._column(source)
        quality = np.clip(quality, 0.0, 1.0)
        conf, support_time_s = self._conf[rows, slots, column], self._time_s[rows, slots, column]
        at_s = np.maximum(time_s, support_time_s)
        current = _decayed(conf, support_time_s, self._fade_s[column], self._decay_per_s[column], at_s)
        matching = quality > 0.0
        self._conf[rows, slots, column] = np.where(
            matching, current + self._gain[column] * (quality * self._max[column] - current), conf)
        self._time_s[rows, slots, column] = np.where(matching, at_s, support_time_s)

    # -- one entry at a time ---------------------------------------------------------------
    # The same equations in plain floats, for a single reading (a V2V message) or a single property's read, where
    # setting up arrays would cost more than the arithmetic.

    def source_confidence_one(self, row: int, slot: int, source: int, time_s: float) -> float:
        """(C1) of one row, slot and source."""
        settings = self._settings_one.get(source)
        if settings is None:  # a source that never supported anything in this table
            return 0.0
        fade_s, decay_per_s, _, _ = settings
        age_s = max(0.0, time_s - self._time_s.item(row, slot, source))
        if age_s > fade_s:
            return 0.0
        return self._conf.item(row, slot, source) * math.exp(-decay_per_s * age_s)

    def confidence_one(self, row: int, slot: int, time_s: float) -> tuple[float, list[int]]:
        """(C3) of one row and slot, and the sources still supporting it."""
        remaining, sources = 1.0, []
        for source in self._columns:
            c = self.source_confidence_one(row, slot, source, time_s)
            if c > 0.0:
                sources.append(source)
                remaining *= 1.0 - c
        return (1.0 - remaining if sources else UNKNOWN_CONFIDENCE), sources

    def support_one(self, row: int, slot: int, source: int, time_s: float, quality: float) -> None:
        """(C2) of one reading of one row and slot."""
        quality = min(1.0, max(0.0, quality))
        if quality == 0.0:
            return
        column = self._column(source)
        at_s = max(time_s, self._time_s.item(row, slot, column))
        current = self.source_confidence_one(row, slot, column, at_s)
        _, _, max_confidence, gain = self._settings_one[column]
        self._conf[row, slot, column] = current + gain * (quality * max_confidence - current)
        self._time_s[row, slot, column] = at_s

    def update_one(self, row: int, slot: int, source: int, time_s: float, value: float, quality: float) -> None:
        """(C4) and (C2) of one reading of one row and slot."""
        old_confidence = max(0.0, self.confidence_one(row, slot, time_s)[0])
        old_value = self._value.item(row, slot)
        if math.isnan(old_value) or old_confidence == 0.0:
            self._value[row, slot] = value
        else:
            bias = self._new_data_bias * (self._closer_bias.item(slot) if value < old_value else 1.0)
            new_weight = bias * self._settings_one[self._column(source)][2] * max(quality, 1e-3)
            self._value[row, slot] = (old_confidence * old_value + new_weight * value) / (old_confidence + new_weight)
        self.support_one(row, slot, source, time_s, quality)

    def _fused(self, conf: np.ndarray, support_time_s: np.ndarray, time_s) -> tuple[np.ndarray, np.ndarray]:
        """(C1) and (C3) over the sources in the last axis of conf and support_time_s at time_s (broadcast against
        the other axes): the fused confidence, -1 where no source supports, and the supporting sources' bit codes."""
        span = self._span
        c = _decayed(conf[..., span], support_time_s[..., span], self._fade_s[span], self._decay_per_s[span],
                     np.asarray(time_s, dtype=float)[..., None])
        codes = (c > 0.0).astype(int) @ _BITS[span]
        return np.where(codes != 0, 1.0 - np.prod(1.0 - c, axis=-1), UNKNOWN_CONFIDENCE), codes

    def _column(self, source: int) -> int:
        if source not in self._columns:
            cfg = self._source_config(source)
            self._fade_s[source], self._decay_per_s[source] = cfg.fade_time_s, cfg.decay_per_s
            self._max[source], self._gain[source] = cfg.max_confidence, cfg.gain
            self._settings_one[source] = (float(self._fade_s[source]), float(self._decay_per_s[source]),
                                          float(self._max[source]), float(self._gain[source]))
            self._columns = sorted(self._columns + [source])
            self._span = slice(self._columns[0], self._columns[-1] + 1)
        return source


def _block(rows, slots) -> tuple[np.ndarray, np.ndarray]:
    """Rows (N, 1) and slots (1, S): indices of an (N, S) block of the table."""
    return np.asarray(rows, dtype=int)[:, None], np.asarray(slots, dtype=int)[None, :]


def _per_row(values) -> np.ndarray:
    """One value per row (N,) as a column (N, 1) of a block; one per row and slot, or one for all, as it is."""
    values = np.asarray(values, dtype=float)
    return values[:, None] if values.ndim == 1 else values


def _decayed(conf, support_time_s, fade_s, decay_per_s, time_s) -> np.ndarray:
    """(C1): c_s(t) = c_s(t_s) exp(-decay_s (t - t_s)), and 0 once t - t_s > fade_s or never supported (t_s -inf)."""
    age_s = np.maximum(0.0, time_s - support_time_s)
    alive = age_s <= fade_s
    return np.where(alive, conf * np.exp(-decay_per_s * np.where(alive, age_s, 0.0)), 0.0)
