"""One property of one object, its confidence and its value: a slot of a SupportTable (support_table.py holds the
equations C1-C4 after the Chalmers scene service), for code that deals with one property at a time.

With every source faded the confidence is -1 and the value is withheld.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .config import SourceConfig
from .support_table import SupportTable
from coopdrive.messages.unknowns import UNKNOWN_CONFIDENCE

__all__ = ["UNKNOWN_CONFIDENCE", "FusedProperty"]


class FusedProperty:
    """One property of one object: value, per-source support, confidence and fade."""

    def __init__(self, source_config: Callable[[int], SourceConfig], new_data_bias: float = 3.0,
                 closer_bias: float = 1.0) -> None:
        """A property with a table of its own; FusedProperty.in_table for one slot of a shared table."""
        table = SupportTable(source_config, 1, new_data_bias, [closer_bias])
        self._bind(table, table.allocate(), 0)

    @classmethod
    def in_table(cls, table: SupportTable, row: int, slot: int) -> FusedProperty:
        prop = cls.__new__(cls)
        prop._bind(table, row, slot)
        return prop

    def _bind(self, table: SupportTable, row: int, slot: int) -> None:
        self._table, self._row, self._rows, self._slot = table, row, np.array([row]), slot

    @property
    def value(self) -> float | None:
        value = float(self._table.values(self._rows)[0, self._slot])
        return None if np.isnan(value) else value

    def source_confidence(self, source: int, time_s: float) -> float:
        """c_s(t), 0 when the source never supported this property or has faded."""
        return self._table.source_confidence_one(self._row, self._slot, source, time_s)

    def support(self, source: int, time_s: float, quality: float = 1.0) -> None:
        """One reading of this property by `source`, matching with quality q in [0, 1]."""
        self._table.support_one(self._row, self._slot, source, time_s, quality)

    def update(self, source: int, time_s: float, value: float, quality: float = 1.0) -> None:
        """Support plus value blending, for properties no filter estimates."""
        self._table.update_one(self._row, self._slot, source, time_s, value, quality)

    def confidence(self, time_s: float) -> float:
        """Fused confidence, or -1 once every supporting source has faded."""
        return self._table.confidence_one(self._row, self._slot, time_s)[0]

    def sources(self, time_s: float) -> list[int]:
        """Sources still supporting the property, in enum order."""
        return self._table.confidence_one(self._row, self._slot, time_s)[1]

    def has_source(self, source: int, time_s: float) -> bool:
        return self.source_confidence(source, time_s) > 0.0

    def valid_until_s(self) -> float:
        """When the last supporting source fades, or -inf if none ever did."""
        return float(self._table.valid_until_s(self._rows)[0, self._slot])

    def last_support_s(self) -> float:
        return float(self._table.last_support_s(self._rows)[0, self._slot])

    def faded(self, time_s: float) -> bool:
        return self.confidence(time_s) == UNKNOWN_CONFIDENCE
