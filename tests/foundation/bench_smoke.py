"""CI's bench smoke: every benchmark of `make bench` at its quick size (bench/sizes.py), in two halves of about the
same time, each a test file of its own, so that the suite's two workers run them side by side."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

from bench import __main__ as bench_runner
from bench.figure import Unit
from bench.sizes import QUICK_VARIABLE

REPO = Path(__file__).resolve().parents[2]
# Every benchmark at its quick size took over five minutes when four other jobs shared this project's 2-core machine
# (load average 20); about 80 s quiet, before the halves.
RUN_TIMEOUT_S = 900
# About 35 s each on a quiet 2-core machine.
SMOKE_HALVES = {
    "first": ["bench_decode", "bench_follow", "bench_geolocation", "bench_record", "bench_security", "bench_startup",
              "bench_v2x", "bench_bus"],
    "second": ["bench_actuation", "bench_control", "bench_gateway_ws", "bench_replay", "bench_scene", "bench_sim",
               "bench_stacks", "bench_world_parts", "bench_sumo"],
}


def python_m_bench(results: Path, *names: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bench", "--results", str(results), *names], cwd=REPO,
                          capture_output=True, text=True, timeout=RUN_TIMEOUT_S, env={**os.environ, QUICK_VARIABLE: "1"})


def check_smoke_half(half: str, results: Path) -> dict:
    """Runs one half; each of its benchmarks must measure finite figures into results.json and print its table.
    Returns the results file's content."""
    names = SMOKE_HALVES[half]
    result = python_m_bench(results, *names)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    written = json.loads(results.read_text())
    assert written["quick"] is True and written["machine"]["cores"] >= 1 and len(written["commit"]["sha"]) == 40
    assert sorted(written["benches"]) == sorted(names) and all(n in bench_runner.benchmark_names() for n in names)
    for name, run in written["benches"].items():
        assert run["failure"] is None and run["figures"], name
        for figure in run["figures"]:
            assert isinstance(figure["value"], float) and math.isfinite(figure["value"]), (name, figure)
            assert (figure["unit"] == Unit.RATIO.value) == (figure["baseline"] is not None), (name, figure)
        # each still prints its table for a person to read
        table = result.stdout.split(f"=== {name}", 1)[1].split(f"({name}: ", 1)[0]
        assert len(table.strip().splitlines()) >= 3, f"{name} printed no table: {table!r}"
    return written
