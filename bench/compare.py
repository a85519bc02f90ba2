"""Compares two `make bench` results: each figure's change from OLD to NEW, and which got worse.

    python -m bench.compare OLD.json NEW.json

A ratio (the code against a baseline measured in the same run) compares between any two runs: it is flagged WORSE
when it moved the wrong way by more than NOISE (10 %), and by more than its own sampling can move it where the
benchmark estimates that (a figure's `spread`, the half-width of its 95 % interval: the two runs' spreads combine
as independent errors do, root of the sum of squares); a change past 10 % but inside that is "within its
interval". An absolute figure (a time, a rate) says as much about the
machine as about the code: it is compared only between runs on the same kind of machine (bench/machine.py), and
then marked "worse (absolute)" past NOISE without failing the comparison, since the load of a shared machine moves
it too. A ratio of CPU times whose sides its benchmark also counts in instructions (its `guarded_by` figure) is
marked "worse in time" past NOISE without failing either: the count, which the load does not move, is flagged
instead when it worsens. A figure a benchmark no longer reports is flagged GONE, one whose benchmark failed NOT MEASURED. Exit
status: 0 nothing flagged, 1 something flagged, 2 a file that is not a results file.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

from rich import box
from rich.console import Console
from rich.table import Table

from bench.figure import Better, Figure, Unit, shown
from bench.results import BenchResults, ResultsError

# A ratio that moved the wrong way by more than this fraction is flagged.
NOISE = 0.10
CONSOLE_WIDTH = 170


class Verdict(Enum):
    BETTER = "better"
    WITHIN_NOISE = "within 10 %"
    WITHIN_INTERVAL = "within its interval"
    WORSE = "WORSE"
    WORSE_ABSOLUTE = "worse (absolute)"
    WORSE_IN_TIME = "worse in time (instructions guard it)"
    OTHER_MACHINE = "not comparable (other machine)"
    NEW_FIGURE = "new figure"
    NOT_RUN = "benchmark not run"
    GONE = "GONE"
    NOT_MEASURED = "NOT MEASURED"


FLAGGED = frozenset({Verdict.WORSE, Verdict.GONE, Verdict.NOT_MEASURED})


@dataclass(frozen=True)
class Change:
    bench: str
    figure: str
    unit: str
    old: float | None
    new: float | None
    verdict: Verdict

    @property
    def relative(self) -> float | None:
        """new / old - 1, when both are there and old is not 0."""
        if self.old is None or self.new is None or self.old == 0:
            return None
        return self.new / self.old - 1


def direction_verdict(old: Figure, new: Figure) -> Verdict:
    """Better, within NOISE or worse, by the figure's own direction."""
    if old.value == 0:
        return Verdict.WITHIN_NOISE if new.value == 0 else Verdict.WORSE
    relative = new.value / old.value - 1
    worse_by = relative if new.better is Better.LOWER else -relative
    if abs(worse_by) > NOISE and abs(worse_by) <= math.hypot(old.spread or 0.0, new.spread or 0.0):
        return Verdict.WITHIN_INTERVAL
    if worse_by > NOISE:
        return Verdict.WORSE
    return Verdict.BETTER if worse_by < -NOISE else Verdict.WITHIN_NOISE


def verdict_of(old: Figure, new: Figure, same_machine: bool, guard_measured: bool = False) -> Verdict:
    """guard_measured: NEW's run also measured the figure that guards `new` (its `guarded_by`)."""
    if not new.measured:
        return Verdict.NOT_MEASURED
    if not new.is_ratio and not same_machine:
        return Verdict.OTHER_MACHINE
    verdict = direction_verdict(old, new)
    if verdict is not Verdict.WORSE:
        return verdict
    if not new.is_ratio:
        return Verdict.WORSE_ABSOLUTE
    return Verdict.WORSE_IN_TIME if guard_measured else verdict


def compare(old: BenchResults, new: BenchResults) -> list[Change]:
    """Every figure of either run, in OLD's order and then NEW's new ones."""
    same_machine = old.machine.same_kind_as(new.machine)
    old_figures, new_figures = old.figures(), new.figures()
    changes = []
    for (bench, name), figure in old_figures.items():
        now = new_figures.get((bench, name))
        if now is not None:
            guard = new_figures.get((bench, now.guarded_by))
            changes.append(Change(bench, name, figure.unit.value, figure.value, now.value,
                                  verdict_of(figure, now, same_machine, guard is not None and guard.measured)))
            continue
        run = new.benches.get(bench)
        verdict = Verdict.NOT_RUN if run is None else Verdict.NOT_MEASURED if run.failure else Verdict.GONE
        changes.append(Change(bench, name, figure.unit.value, figure.value, None, verdict))
    changes += [Change(bench, name, figure.unit.value, None, figure.value, Verdict.NEW_FIGURE)
                for (bench, name), figure in new_figures.items() if (bench, name) not in old_figures]
    # A benchmark that failed in NEW and had nothing in OLD to miss is flagged by itself.
    measured_before = {bench for bench, _ in old_figures}
    changes += [Change(bench, f"(failed: {failure})", "", None, None, Verdict.NOT_MEASURED)
                for bench, failure in new.failures().items() if bench not in measured_before]
    return changes


def unguarded_ratios(results: BenchResults) -> list[tuple[str, str]]:
    """(bench, figure) of every ratio with neither an interval (`spread`) nor an instruction count that guards it,
    and not a count itself: a ratio that only NOISE guards, which the machine's load alone may flag."""
    return [(bench, name) for (bench, name), figure in results.figures().items()
            if figure.is_ratio and figure.spread is None and figure.guarded_by is None
            and not name.endswith(", instructions")]


def print_changes(old: BenchResults, new: BenchResults, changes: list[Change], console: Console) -> None:
    for label, results in (("OLD", old), ("NEW", new)):
        console.print(f"{label}: {results.commit.describe()} on {results.machine.describe()}", highlight=False)
    if not old.machine.same_kind_as(new.machine):
        console.print("Other machines: only ratios are compared.", highlight=False)
    table = Table(box=box.SIMPLE_HEAD, pad_edge=False)
    for column, justify in (("benchmark", "left"), ("figure", "left"), ("unit", "left"), ("old", "right"),
                            ("new", "right"), ("change", "right"), ("verdict", "left")):
        table.add_column(column, justify=justify)
    for change in changes:
        table.add_row(change.bench.removeprefix("bench_"), change.figure, change.unit,
                      "" if change.old is None else shown(change.old), "" if change.new is None else shown(change.new),
                      "" if change.relative is None else f"{100 * change.relative:+.1f} %", change.verdict.value)
    console.print(table, highlight=False)
    flagged = [change for change in changes if change.verdict in FLAGGED]
    ratios = sum(1 for change in changes if change.unit == Unit.RATIO.value)
    console.print(f"{len(changes)} figures, {ratios} of them ratios; {len(flagged)} flagged"
                  + "".join(f"\n  {c.verdict.value}: {c.bench} {c.figure}" for c in flagged), highlight=False)
    bare = unguarded_ratios(new)
    if bare:
        console.print(f"{len(bare)} ratios of NEW have neither an interval nor an instruction count, only the 10 % "
                      "guards them:" + "".join(f"\n  {bench} {name}" for bench, name in bare), highlight=False)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.compare", description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path, help="results.json of the run before")
    parser.add_argument("new", type=Path, help="results.json of the run after")
    args = parser.parse_args(argv)
    try:
        old, new = BenchResults.load(args.old), BenchResults.load(args.new)
    except ResultsError as error:
        print(f"bench.compare: {error}", file=sys.stderr)
        return 2
    if old.quick != new.quick:
        print("bench.compare: one run has the quick sizes (COOPDRIVE_BENCH_QUICK=1) and the other the full ones: "
              "their figures do not compare", file=sys.stderr)
        return 2
    changes = compare(old, new)
    print_changes(old, new, changes, Console(width=CONSOLE_WIDTH))
    return 1 if any(change.verdict in FLAGGED for change in changes) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
