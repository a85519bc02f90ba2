"""Runs every benchmark module in bench/ and prints their tables; `python -m bench NAME` runs those whose names
contain NAME. Each benchmark's main() prints its table and returns its figures (bench/figure.py); they go to
bench/results.json (`--results PATH` elsewhere) with the machine and the commit. A benchmark that fails, or
measured nothing, is named with a one-line reason and the run exits 1; the others still run."""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import sys
import time
from pathlib import Path

import bench
from bench.failure import BenchFailed
from bench.results import DEFAULT_PATH, BenchResults
from bench.sizes import QUICK_VARIABLE


def benchmark_names() -> list[str]:
    """Every benchmark module of bench/, in the order `make bench` runs them."""
    return sorted(m.name for m in pkgutil.iter_modules(bench.__path__) if m.name.startswith("bench_"))


def one_line(error: BaseException) -> str:
    """A benchmark's own BenchFailed says why in its words; anything else is named by its type."""
    if isinstance(error, BenchFailed):
        return str(error)
    text = f"{error!r}".splitlines()
    return text[0] if text else type(error).__name__


def run_one(name: str, results: BenchResults) -> str | None:
    """Runs benchmark `name` into `results`; why it failed, or None."""
    started = time.monotonic()
    runner_argv, sys.argv = sys.argv, [f"bench.{name}"]  # the names selected are not the benchmark's options
    try:
        figures = importlib.import_module(f"bench.{name}").main()
    except (Exception, SystemExit) as error:  # one broken benchmark must not hide the others
        results.fail(name, one_line(error), time.monotonic() - started)
        return one_line(error)
    finally:
        sys.argv = runner_argv
    return results.add(name, figures, time.monotonic() - started)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench", description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="run only the benchmarks whose names contain one of these")
    parser.add_argument("--results", type=Path, default=DEFAULT_PATH, help=f"where to write (default {DEFAULT_PATH})")
    args = parser.parse_args(argv)
    names = [n for n in benchmark_names() if not args.names or any(s in n for s in args.names)]
    results = BenchResults.starting_now(quick=os.environ.get(QUICK_VARIABLE) == "1")
    for name in names:
        print(f"\n=== {name}", flush=True)
        failure = run_one(name, results)
        if failure is not None:
            print(f"{name} failed: {failure}")
        print(f"({name}: {results.benches[name].seconds:.1f} s)", flush=True)
    results.write(args.results)
    failures = results.failures()
    print(f"\n{len(names) - len(failures)} of {len(names)} benchmarks measured; results in {args.results}")
    for name, failure in failures.items():
        print(f"FAILED {name}: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
