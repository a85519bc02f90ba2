"""Per-property confidence after the Chalmers scene service (Svensson 2017, Sect. 3.5 and 4.3.1).

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
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from .config import SourceConfig

UNKNOWN_CONFIDENCE = -1.0


@dataclass
class _Support:
    confidence: float
    time_s: float


class FusedProperty:
    """One property of one object: value, per-source support, confidence and fade."""

    def __init__(
        self,
        source_config: Callable[[int], SourceConfig],
        new_data_bias: float = 3.0,
        closer_bias: float = 1.0,
    ) -> None:
        self._source_config = source_config
        self._new_data_bias = new_data_bias
        self._closer_bias = closer_bias
        self._support: dict[int, _Support] = {}
        self.value: float | None = None

    def source_confidence(self, source: int, time_s: float) -> float:
        """c_s(t), 0 when the source never supported this property or has faded."""
        support = self._support.get(source)
        if support is None:
            return 0.0
        cfg = self._source_config(source)
        age = max(0.0, time_s - support.time_s)
        if age > cfg.fade_time_s:
            return 0.0
        return support.confidence * math.exp(-cfg.decay_per_s * age)  # (C1)

    def support(self, source: int, time_s: float, quality: float = 1.0) -> None:
        """One reading of this property by `source`, matching with quality q in [0, 1]."""
        quality = min(1.0, max(0.0, quality))
        if quality == 0.0:
            # A reading that matches not at all supports nothing, and must not keep the property alive.
            return
        cfg = self._source_config(source)
        previous = self._support.get(source)
        # A late reading never moves the support time backwards, and does not decay into the future.
        at_s = max(time_s, previous.time_s) if previous else time_s
        current = self.source_confidence(source, at_s)
        raised = current + cfg.gain * (quality * cfg.max_confidence - current)  # (C2)
        self._support[source] = _Support(confidence=raised, time_s=at_s)

    def update(self, source: int, time_s: float, value: float, quality: float = 1.0) -> None:
        """Support plus value blending (C4), for properties no filter estimates."""
        old_confidence = max(0.0, self.confidence(time_s))
        if self.value is None or old_confidence == 0.0:
            self.value = value
        else:
            cfg = self._source_config(source)
            bias = self._new_data_bias
            if value < self.value:
                bias *= self._closer_bias
            new_weight = bias * cfg.max_confidence * max(quality, 1e-3)
            self.value = (old_confidence * self.value + new_weight * value) / (old_confidence + new_weight)  # (C4)
        self.support(source, time_s, quality)

    def confidence(self, time_s: float) -> float:
        """Fused confidence (C3), or -1 once every supporting source has faded."""
        remaining = 1.0
        alive = False
        for source in self._support:
            c = self.source_confidence(source, time_s)
            if c > 0.0:
                alive = True
                remaining *= 1.0 - c
        return 1.0 - remaining if alive else UNKNOWN_CONFIDENCE  # (C3)

    def sources(self, time_s: float) -> list[int]:
        """Sources still supporting the property, in enum order."""
        return sorted(s for s in self._support if self.source_confidence(s, time_s) > 0.0)

    def has_source(self, source: int, time_s: float) -> bool:
        return self.source_confidence(source, time_s) > 0.0

    def valid_until_s(self) -> float:
        """When the last supporting source fades, or -inf if none ever did."""
        ends = [s.time_s + self._source_config(src).fade_time_s for src, s in self._support.items()]
        return max(ends, default=-math.inf)

    def last_support_s(self) -> float:
        return max((s.time_s for s in self._support.values()), default=-math.inf)

    def faded(self, time_s: float) -> bool:
        return self.confidence(time_s) == UNKNOWN_CONFIDENCE
