"""The current figures as Markdown, generated from a results file: `make bench` writes bench/results.json, and

    python -m bench.report bench/results.json                           prints the tables
    python -m bench.report bench/results.json --write docs/performance.md

replaces what lies between the markers below in that page (tests/foundation/test_bench_report.py holds the page to
what this makes of docs/bench-results.json)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from bench.figure import shown
from bench.results import BenchResults, ResultsError

START_MARKER = "<!-- bench-table:start -->"
END_MARKER = "<!-- bench-table:end -->"


class ReportError(Exception):
    pass


def tables(results: BenchResults) -> str:
    """One table per benchmark: each figure, its value and unit, the half-width of its 95 % interval where the
    benchmark estimates one, and what a ratio is to."""
    sizes = "at the quick sizes, whose figures mean nothing," if results.quick else "at full size"
    lines = [f"Measured by `make bench` {sizes} on {results.machine.describe()}. Absolute figures are this "
             "machine's; ratios are to a baseline measured in the same run."]
    for bench, run in results.benches.items():
        lines += ["", f"**{bench}** ({run.seconds:.0f} s)", ""]
        if run.failure:
            lines.append(f"Failed: {run.failure}")
            continue
        lines += ["| figure | value | 95 % interval | unit | ratio to |", "|---|--:|--:|---|---|"]
        lines += [f"| {figure.name} | {shown(figure.value)} | {_interval(figure.spread)} | {figure.unit.value} "
                  f"| {figure.baseline or ''} |" for figure in run.figures]
    return "\n".join(lines)


def _interval(spread: float | None) -> str:
    return "" if spread is None else f"+-{100 * spread:.0f} %"


def with_tables(page: str, generated: str) -> str:
    """`page` with what lies between its markers replaced by `generated`."""
    if page.count(START_MARKER) != 1 or page.count(END_MARKER) != 1 or page.index(START_MARKER) > page.index(END_MARKER):
        raise ReportError(f"the page needs one {START_MARKER} and, after it, one {END_MARKER}")
    before, rest = page.split(START_MARKER)
    after = rest.split(END_MARKER)[1]
    return f"{before}{START_MARKER}\n{generated}\n{END_MARKER}{after}"


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.report", description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path)
    parser.add_argument("--write", type=Path, metavar="PAGE", help="replace the tables between the page's markers")
    args = parser.parse_args(argv)
    try:
        generated = tables(BenchResults.load(args.results))
        if args.write is None:
            print(generated)
        else:
            args.write.write_text(with_tables(args.write.read_text(), generated))
    except (ResultsError, ReportError, OSError) as error:
        print(f"bench.report: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
