"""`make bench` is `python -m bench`: every benchmark in bench/ in turn, or those named. These tests check that it
runs and reports, not how fast anything is (speed is the benchmarks' own business, never a test's)."""

import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from bench import __main__ as bench_runner
from bench.sizes import QUICK_VARIABLE

pytestmark = pytest.mark.whole_run

REPO = Path(__file__).resolve().parents[2]
# Every benchmark at its quick size takes about a minute on this project's 2-core machine.
RUN_TIMEOUT_S = 600


def python_m_bench(*names: str) -> subprocess.CompletedProcess:
    result = subprocess.run([sys.executable, "-m", "bench", *names], cwd=REPO, capture_output=True, text=True,
                            timeout=RUN_TIMEOUT_S, env={**os.environ, QUICK_VARIABLE: "1"})
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return result


def test_every_benchmark_of_make_bench_runs_to_the_end_and_prints_its_table():
    names = bench_runner.benchmark_names()
    assert len(names) >= 14
    out = python_m_bench().stdout
    assert "failed" not in out
    for name in names:
        assert f"=== {name}" in out and f"({name}: " in out
        table = out.split(f"=== {name}", 1)[1].split(f"({name}: ", 1)[0]
        assert len(table.strip().splitlines()) >= 3, f"{name} printed no table: {table!r}"


def test_python_m_bench_with_names_runs_only_those_benchmarks_and_exits_0():
    result = python_m_bench("geolocation", "sim")
    assert "=== bench_geolocation" in result.stdout and "=== bench_sim" in result.stdout
    assert "failed" not in result.stdout
    assert "=== bench_follow" not in result.stdout
    # Each prints its table: the geolocation filter beside filterpy's, the simulator's CPU per simulated second.
    assert "GeolocationEkf CTRA predict+gated update" in result.stdout
    assert "CPU ms per simulated s" in result.stdout


def test_a_benchmark_that_fails_or_exits_is_named_and_the_others_still_run(monkeypatch, capsys):
    ran = []

    def fake_module(name: str):
        def main():
            ran.append(name)
            if name == "bench.bench_control":
                raise ValueError("shapes not aligned")
            if name == "bench.bench_decode":
                sys.exit(2)  # as argparse does on options it does not know

        return SimpleNamespace(main=main)

    monkeypatch.setattr(bench_runner.importlib, "import_module", fake_module)
    assert bench_runner.main(["actuation", "control", "decode"]) == 1
    assert ran == ["bench.bench_actuation", "bench.bench_control", "bench.bench_decode"]
    out = capsys.readouterr().out
    assert "bench_control failed: ValueError('shapes not aligned')" in out
    assert "bench_decode failed: SystemExit(2)" in out
    assert "bench_actuation failed" not in out


def test_a_benchmark_sees_none_of_the_runner_s_arguments_as_its_options(monkeypatch):
    seen = []
    monkeypatch.setattr(bench_runner.importlib, "import_module",
                        lambda name: SimpleNamespace(main=lambda: seen.append(list(sys.argv[1:]))))
    monkeypatch.setattr(sys, "argv", ["bench", "geolocation"])
    assert bench_runner.main(["geolocation"]) == 0
    assert seen == [[]]
    assert sys.argv == ["bench", "geolocation"]
