"""BenchResults: what one `make bench` measured, as bench/results.json: each benchmark's figures (bench/figure.py),
how long it took and why it failed if it did, the machine (bench/machine.py), the commit and whether the tree had
changes, and whether the sizes were the quick ones (bench/sizes.py).

It is also where a benchmark that measured nothing is caught, once for all of them: no figures, a figure that is not
a finite number, or the same name twice fail the benchmark with a one-line reason naming the figure.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from bench.commit import REPOSITORY, Commit
from bench.figure import Figure
from bench.machine import Machine

FORMAT = 1
DEFAULT_PATH = REPOSITORY / "bench" / "results.json"


class ResultsError(Exception):
    """A results file that cannot be read, with a one-line reason."""


@dataclass
class BenchRun:
    seconds: float
    figures: list[Figure] = field(default_factory=list)
    failure: str | None = None


def failure_of(figures: object) -> str | None:
    """Why what a benchmark's main() returned is not a measurement, or None if it is one."""
    if not isinstance(figures, list) or not figures:
        return "measured nothing: it reported no figures"
    names: set[str] = set()
    for figure in figures:
        if not isinstance(figure, Figure):
            return f"reported {figure!r}, not a Figure"
        if not figure.measured:
            return f"figure {figure.name!r} is {figure.value}: nothing was measured for it"
        if figure.name in names:
            return f"figure {figure.name!r} reported twice"
        names.add(figure.name)
    return None


class BenchResults:
    def __init__(self, machine: Machine, commit: Commit, quick: bool):
        self.machine = machine
        self.commit = commit
        self.quick = quick
        self.benches: dict[str, BenchRun] = {}

    @classmethod
    def starting_now(cls, quick: bool) -> BenchResults:
        return cls(Machine.now(), Commit.now(), quick)

    def add(self, bench: str, figures: object, seconds: float) -> str | None:
        """Takes what bench's main() returned; returns why it is not a measurement, or None."""
        failure = failure_of(figures)
        self.benches[bench] = BenchRun(seconds, [] if failure else list(figures), failure)
        return failure

    def fail(self, bench: str, reason: str, seconds: float) -> None:
        self.benches[bench] = BenchRun(seconds, [], reason)

    def failures(self) -> dict[str, str]:
        return {name: run.failure for name, run in self.benches.items() if run.failure is not None}

    def figures(self) -> dict[tuple[str, str], Figure]:
        """Every figure by (benchmark, figure name)."""
        return {(bench, figure.name): figure for bench, run in self.benches.items() for figure in run.figures}

    def as_json(self) -> dict:
        return {"format": FORMAT, "commit": {"sha": self.commit.sha, "dirty": self.commit.dirty},
                "machine": self.machine.as_json(), "quick": self.quick,
                "benches": {name: {"seconds": round(run.seconds, 1), "failure": run.failure,
                                   "figures": [figure.as_json() for figure in run.figures]}
                            for name, run in self.benches.items()}}

    def write(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(self.as_json(), indent=1) + "\n")

    @classmethod
    def load(cls, path: Path) -> BenchResults:
        try:
            data = json.loads(Path(path).read_text())
        except (OSError, ValueError) as error:
            raise ResultsError(f"{path}: not a results file ({error})") from None
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise ResultsError(f"{path}: not a results file of format {FORMAT} (written by `make bench`)")
        try:
            results = cls(Machine.from_json(data["machine"]), Commit(**data["commit"]), bool(data["quick"]))
            for name, run in data["benches"].items():
                results.benches[name] = BenchRun(float(run["seconds"]),
                                                 [Figure.from_json(row) for row in run["figures"]], run["failure"])
        except (KeyError, TypeError, ValueError) as error:
            raise ResultsError(f"{path}: a results file missing or misspelling {error}") from None
        return results
