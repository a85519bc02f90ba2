"""Runs every benchmark module in bench/ and prints their tables; `python -m bench NAME` runs one."""

import importlib
import pkgutil
import sys
import time

import bench


def benchmark_names() -> list[str]:
    """Every benchmark module of bench/, in the order `make bench` runs them."""
    return sorted(m.name for m in pkgutil.iter_modules(bench.__path__) if m.name.startswith("bench_"))


def main(selected: list[str]) -> int:
    names = benchmark_names()
    if selected:
        names = [n for n in names if any(s in n for s in selected)]
    failures = 0
    for name in names:
        started = time.monotonic()
        print(f"\n=== {name}", flush=True)
        runner_argv, sys.argv = sys.argv, [f"bench.{name}"]  # the names selected are not the benchmark's options
        try:
            importlib.import_module(f"bench.{name}").main()
        except (Exception, SystemExit) as error:  # one broken benchmark must not hide the others
            failures += 1
            print(f"{name} failed: {error!r}")
        finally:
            sys.argv = runner_argv
        print(f"({name}: {time.monotonic() - started:.1f} s)", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
