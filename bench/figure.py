"""Figure: one number a benchmark measured, as `make bench` writes it to bench/results.json and compares it.

A figure is absolute (a time, a rate: it says as much about the machine as about the code) or a ratio to a
baseline measured in the same run on the same machine (the code against the path it replaced, against a bare
library doing the same work): a ratio can be compared between machines and between runs on a loaded one, an
absolute figure only between runs on the same machine (bench/compare.py).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from enum import Enum


class Unit(Enum):
    US = "us"
    MS = "ms"
    S = "s"
    PER_S = "per s"
    MS_PER_SIMULATED_S = "ms per simulated s"
    # Simulated seconds per wall second: a run's real-time factor.
    REALTIME_FACTOR = "x real time"
    MIB = "MiB"
    RATIO = "ratio"


class Better(Enum):
    """Which way a figure improves."""
    LOWER = "lower"
    HIGHER = "higher"


# Units whose figures improve upwards; every other unit is a cost (a time, memory).
HIGHER_IS_BETTER = frozenset({Unit.PER_S, Unit.REALTIME_FACTOR})


@dataclass(frozen=True)
class Figure:
    """`name` is unique within its benchmark and stable from commit to commit (compare matches figures by it).
    A ratio names its `baseline`, what it is divided by, and says which way it improves; an absolute figure's
    direction follows from its unit. `spread`: where the benchmark can estimate how far its own sampling may move
    the figure (a percentile of a few hundred latencies), the half-width of its 95 % interval over the value
    (0.2: the interval is the value +- 20 %); bench/compare.py flags a change only beyond it. `guarded_by`: a
    ratio of CPU times whose two sides the benchmark also counts in instructions (bench/instructions_per_call.py)
    names that count's figure, which the machine's load does not move; compare flags the count, not the time."""
    name: str
    value: float
    unit: Unit
    baseline: str | None = None
    better: Better | None = None
    spread: float | None = None
    guarded_by: str | None = None

    def __post_init__(self) -> None:
        if (self.unit is Unit.RATIO) != (self.baseline is not None):
            raise ValueError(f"figure {self.name!r}: a ratio, and only a ratio, names its baseline")
        if self.better is None:
            if self.unit is Unit.RATIO:
                raise ValueError(f"figure {self.name!r}: a ratio says whether lower or higher is better")
            object.__setattr__(self, "better", Better.HIGHER if self.unit in HIGHER_IS_BETTER else Better.LOWER)

    @property
    def is_ratio(self) -> bool:
        return self.unit is Unit.RATIO

    @property
    def measured(self) -> bool:
        """A finite number: NaN and infinities are what an empty or broken measurement leaves."""
        return isinstance(self.value, (int, float)) and math.isfinite(self.value)

    def as_json(self) -> dict:
        row = asdict(self)
        row["unit"], row["better"] = self.unit.value, self.better.value
        # JSON has no NaN: a broken figure is written as null (and the run fails on it).
        row["value"] = float(self.value) if self.measured else None
        return row

    @classmethod
    def from_json(cls, row: dict) -> Figure:
        value = math.nan if row["value"] is None else float(row["value"])
        return cls(row["name"], value, Unit(row["unit"]), row.get("baseline"), Better(row["better"]),
                   row.get("spread"), row.get("guarded_by"))


def ratio(name: str, value: float, baseline: str, better: Better = Better.LOWER,
          spread: float | None = None, guarded_by: str | None = None) -> Figure:
    """A ratio figure: `value` is this figure over `baseline`'s, both measured in the same run."""
    return Figure(name, value, Unit.RATIO, baseline, better, spread, guarded_by)


def instruction_ratio(name: str, value: float, baseline: str, better: Better = Better.LOWER) -> Figure:
    """A ratio of two instruction counts (bench/instructions_per_call.py): named as such, so that a reader of the
    results tells it from a ratio of times."""
    return ratio(f"{name}, instructions", value, f"{baseline}, instructions", better)


def shown(value: float) -> str:
    """A figure's value to three significant digits or so, without exponents: 0.0123, 1.23, 12.3, 1,234."""
    if not math.isfinite(value):
        return str(value)
    magnitude = abs(value)
    if magnitude >= 100:
        return f"{value:,.0f}"
    if magnitude >= 10:
        return f"{value:.1f}"
    if magnitude >= 1:
        return f"{value:.2f}"
    return f"{value:.3g}"
