"""`make bench` is `python -m bench`: every benchmark in bench/ in turn, or those named, each reporting its figures
into bench/results.json. These tests check that one that measured nothing fails naming the figure, not how fast
anything is (speed is the benchmarks' own business, never a test's). CI's bench smoke, every benchmark at its quick
size, is in two halves beside this file (bench_smoke.py)."""

import json
import math
import sys
from types import SimpleNamespace

import pytest

from bench import __main__ as bench_runner
from bench import bench_gateway_ws
from bench.bench_gateway_ws import DURATION_ENV
from bench.figure import Figure, Unit
from tests.foundation.bench_smoke import SMOKE_HALVES, python_m_bench

pytestmark = pytest.mark.whole_run

GATEWAY_RUN_S = 1.0


def test_ci_s_bench_smoke_runs_every_benchmark_of_make_bench_in_one_of_its_two_halves():
    assert sorted(SMOKE_HALVES["first"] + SMOKE_HALVES["second"]) == bench_runner.benchmark_names()


def test_python_m_bench_with_names_runs_only_those_benchmarks_and_writes_only_theirs(tmp_path):
    # The two quickest: what is checked is the choosing, which any benchmark shows.
    result = python_m_bench(tmp_path / "results.json", "control", "world_parts")
    assert result.returncode == 0, result.stdout[-3000:]
    assert "=== bench_control" in result.stdout and "=== bench_world_parts" in result.stdout
    assert "=== bench_follow" not in result.stdout
    assert list(json.loads((tmp_path / "results.json").read_text())["benches"]) == ["bench_control",
                                                                                    "bench_world_parts"]
    # Each prints its table: the control laws' call times, each world part beside the general path it replaced.
    assert "law: our CACC" in result.stdout
    assert "general path us" in result.stdout


def fake_benchmarks(monkeypatch, mains: dict) -> list[str]:
    """The runner imports these instead of the benchmarks: module name -> its main()."""
    ran = []

    def fake_module(name: str):
        def main():
            ran.append(name)
            return mains[name]()
        return SimpleNamespace(main=main)

    monkeypatch.setattr(bench_runner.importlib, "import_module", fake_module)
    return ran


def a_figure():
    return [Figure("p50", 1.0, Unit.MS)]


def test_a_benchmark_that_fails_or_exits_is_named_and_the_others_still_run(monkeypatch, capsys, tmp_path):
    def shapes():
        raise ValueError("shapes not aligned")

    def argparse_exit():
        sys.exit(2)  # as argparse does on options it does not know

    ran = fake_benchmarks(monkeypatch, {"bench.bench_actuation": a_figure, "bench.bench_control": shapes,
                                        "bench.bench_decode": argparse_exit})
    assert bench_runner.main(["actuation", "control", "decode", "--results", str(tmp_path / "r.json")]) == 1
    assert ran == ["bench.bench_actuation", "bench.bench_control", "bench.bench_decode"]
    out = capsys.readouterr().out
    assert "bench_control failed: ValueError('shapes not aligned')" in out
    assert "bench_decode failed: SystemExit(2)" in out
    assert "bench_actuation failed" not in out
    assert "FAILED bench_control: ValueError('shapes not aligned')" in out
    written = json.loads((tmp_path / "r.json").read_text())["benches"]
    assert written["bench_actuation"]["figures"][0]["value"] == 1.0
    assert written["bench_control"]["failure"] == "ValueError('shapes not aligned')"


@pytest.mark.parametrize("figures, reason", [
    (lambda: None, "measured nothing: it reported no figures"),
    (lambda: [], "measured nothing: it reported no figures"),
    (lambda: [Figure("0 clients: sensor -> command p99", math.nan, Unit.MS)],
     "figure '0 clients: sensor -> command p99' is nan: nothing was measured for it"),
    (lambda: [Figure("p50", 1.0, Unit.MS), Figure("p50", 2.0, Unit.MS)], "figure 'p50' reported twice"),
])
def test_a_benchmark_that_measured_nothing_exits_non_zero_naming_the_figure(monkeypatch, capsys, tmp_path, figures,
                                                                             reason):
    fake_benchmarks(monkeypatch, {"bench.bench_follow": figures})
    assert bench_runner.main(["follow", "--results", str(tmp_path / "r.json")]) == 1
    assert f"FAILED bench_follow: {reason}\n" in capsys.readouterr().out


def test_a_benchmark_sees_none_of_the_runner_s_arguments_as_its_options(monkeypatch, tmp_path):
    seen = []
    fake_benchmarks(monkeypatch, {"bench.bench_geolocation": lambda: seen.append(list(sys.argv[1:])) or a_figure()})
    monkeypatch.setattr(sys, "argv", ["bench", "geolocation"])
    assert bench_runner.main(["geolocation", "--results", str(tmp_path / "r.json")]) == 0
    assert seen == [[]]
    assert sys.argv == ["bench", "geolocation"]


def test_the_gateway_bench_whose_gateway_never_starts_fails_in_one_line_saying_so(monkeypatch, capsys, tmp_path):
    real_run = bench_gateway_ws.run_scenario
    monkeypatch.setattr(bench_gateway_ws, "run_scenario",
                        lambda options: real_run(options.__class__(**{**vars(options), "gateway_port": None})))
    monkeypatch.setenv(DURATION_ENV, str(GATEWAY_RUN_S))
    assert bench_runner.main(["gateway", "--results", str(tmp_path / "r.json")]) == 1
    assert ("FAILED bench_gateway_ws: the run started no gateway process (the launcher told of none)\n"
            in capsys.readouterr().out)
