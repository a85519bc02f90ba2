"""`python -m bench.compare OLD NEW` on results files written by hand: what it flags, what it leaves alone, and what
it refuses to compare."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from bench import compare as bench_compare
from bench.compare import Verdict, compare
from bench.results import BenchResults

REPO = Path(__file__).resolve().parents[2]
HERE = {"cpu_model": "AMD EPYC", "cores": 2, "load_1m_at_start": 0.4, "python": "3.11.7"}
ELSEWHERE = {**HERE, "cpu_model": "Intel(R) Core(TM) i7-8565U", "cores": 8}


def figure(name: str, value: float | None, unit: str = "ms", baseline: str | None = None,
           better: str | None = None) -> dict:
    """A figure as results.json holds it; a rate is better higher, a time lower."""
    better = better or ("higher" if unit == "per s" else "lower")
    return {"name": name, "value": value, "unit": unit, "baseline": baseline, "better": better}


def bus(p50_us: float | None, ratio: float | None) -> dict:
    """bench_bus as the runner writes it: an absolute figure and a ratio."""
    return {"seconds": 12.0, "failure": None, "figures": [
        figure("coopdrive typed p50", p50_us, "us"),
        figure("coopdrive typed p50 to raw", ratio, "ratio", "raw zenoh bytes p50")]}


def results(tmp_path: Path, name: str, benches: dict, machine: dict = HERE, quick: bool = False) -> Path:
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps({"format": 1, "commit": {"sha": "0123456789abcdef", "dirty": False},
                                "machine": machine, "quick": quick, "benches": benches}))
    return path


def verdicts(tmp_path: Path, old: dict, new: dict, new_machine: dict = HERE) -> dict[str, Verdict]:
    changes = compare(BenchResults.load(results(tmp_path, "old", old)),
                      BenchResults.load(results(tmp_path, "new", new, new_machine)))
    return {change.figure: change.verdict for change in changes}


def test_a_ratio_worse_by_more_than_10_percent_is_flagged_and_the_comparison_exits_1(tmp_path, capsys):
    old, new = results(tmp_path, "old", {"bench_bus": bus(100.0, 1.50)}), results(tmp_path, "new", {
        "bench_bus": bus(100.0, 1.70)})
    assert bench_compare.main([str(old), str(new)]) == 1
    out = capsys.readouterr().out
    assert "WORSE: bench_bus coopdrive typed p50 to raw" in out and "+13.3 %" in out


def test_ratios_within_10_percent_either_way_or_better_are_not_flagged_and_the_comparison_exits_0(tmp_path):
    assert verdicts(tmp_path, {"bench_bus": bus(100.0, 1.50)}, {"bench_bus": bus(100.0, 1.60)}) == {
        "coopdrive typed p50": Verdict.WITHIN_NOISE, "coopdrive typed p50 to raw": Verdict.WITHIN_NOISE}
    assert verdicts(tmp_path, {"bench_bus": bus(100.0, 1.50)}, {"bench_bus": bus(80.0, 1.20)}) == {
        "coopdrive typed p50": Verdict.BETTER, "coopdrive typed p50 to raw": Verdict.BETTER}
    old, new = results(tmp_path, "old", {"bench_bus": bus(100.0, 1.5)}), results(tmp_path, "new", {
        "bench_bus": bus(80.0, 1.2)})
    assert bench_compare.main([str(old), str(new)]) == 0


def gateway(p99_ratio: float, spread: float | None) -> dict:
    """bench_gateway_ws's p99 ratio with the half-width of its 95 % interval."""
    return {"seconds": 60.0, "failure": None, "figures": [
        {**figure("50 clients: p99 to 0 clients'", p99_ratio, "ratio", "0 clients: sensor -> command p99"),
         "spread": spread}]}


def test_a_ratio_worse_by_more_than_10_percent_but_inside_both_runs_intervals_is_not_flagged(tmp_path):
    # 24 % worse; the two runs' spreads of 20 % and 15 % combine to 25 %.
    assert verdicts(tmp_path, {"bench_gateway_ws": gateway(1.00, 0.20)}, {"bench_gateway_ws": gateway(1.24, 0.15)}) == {
        "50 clients: p99 to 0 clients'": Verdict.WITHIN_INTERVAL}


def test_a_ratio_worse_beyond_its_combined_interval_is_flagged(tmp_path):
    assert verdicts(tmp_path, {"bench_gateway_ws": gateway(1.00, 0.10)}, {"bench_gateway_ws": gateway(1.24, 0.15)}) == {
        "50 clients: p99 to 0 clients'": Verdict.WORSE}
    assert verdicts(tmp_path, {"bench_gateway_ws": gateway(1.00, None)}, {"bench_gateway_ws": gateway(1.24, None)}) == {
        "50 clients: p99 to 0 clients'": Verdict.WORSE}


def test_a_figure_where_higher_is_better_is_worse_when_it_falls(tmp_path):
    def v2x(decodes_per_s: float, times_bare: float) -> dict:
        return {"bench_v2x": {"seconds": 1.0, "failure": None, "figures": [
            figure("CAM decodes", decodes_per_s, "per s"),
            figure("CAM speed-up", times_bare, "ratio", "CAM bare decodes", "higher")]}}
    assert verdicts(tmp_path, v2x(1000.0, 2.0), v2x(850.0, 1.7)) == {"CAM decodes": Verdict.WORSE_ABSOLUTE,
                                                                     "CAM speed-up": Verdict.WORSE}
    assert verdicts(tmp_path, v2x(1000.0, 2.0), v2x(1200.0, 2.3)) == {"CAM decodes": Verdict.BETTER,
                                                                      "CAM speed-up": Verdict.BETTER}


def test_an_absolute_figure_slower_on_the_same_machine_is_marked_but_does_not_fail_the_comparison(tmp_path):
    old, new = results(tmp_path, "old", {"bench_bus": bus(100.0, 1.5)}), results(tmp_path, "new", {
        "bench_bus": bus(150.0, 1.5)})
    assert verdicts(tmp_path, {"bench_bus": bus(100.0, 1.5)}, {"bench_bus": bus(150.0, 1.5)})[
        "coopdrive typed p50"] is Verdict.WORSE_ABSOLUTE
    assert bench_compare.main([str(old), str(new)]) == 0


def test_absolute_figures_from_another_machine_are_not_compared_but_its_ratios_are(tmp_path, capsys):
    assert verdicts(tmp_path, {"bench_bus": bus(100.0, 1.5)}, {"bench_bus": bus(400.0, 1.9)}, ELSEWHERE) == {
        "coopdrive typed p50": Verdict.OTHER_MACHINE, "coopdrive typed p50 to raw": Verdict.WORSE}
    bench_compare.main([str(tmp_path / "old.json"), str(tmp_path / "new.json")])
    out = capsys.readouterr().out
    assert "not comparable (other machine)" in out and "Other machines: only ratios are compared." in out


def test_a_figure_gone_from_a_benchmark_that_ran_is_flagged_and_a_new_one_is_listed(tmp_path):
    old = {"bench_bus": bus(100.0, 1.5)}
    new = {"bench_bus": {"seconds": 1.0, "failure": None, "figures": [
        figure("coopdrive typed p50", 100.0, "us"), figure("coopdrive typed p99", 140.0, "us")]}}
    assert verdicts(tmp_path, old, new) == {"coopdrive typed p50": Verdict.WITHIN_NOISE,
                                            "coopdrive typed p50 to raw": Verdict.GONE,
                                            "coopdrive typed p99": Verdict.NEW_FIGURE}


def test_figures_of_a_benchmark_that_failed_or_got_nan_are_flagged_not_measured(tmp_path):
    failed = {"bench_bus": {"seconds": 3.0, "failure": "the run 'one per service' failed: timeout", "figures": []}}
    assert set(verdicts(tmp_path, {"bench_bus": bus(100.0, 1.5)}, failed).values()) == {Verdict.NOT_MEASURED}
    assert verdicts(tmp_path, {"bench_bus": bus(100.0, 1.5)}, {"bench_bus": bus(100.0, None)})[
        "coopdrive typed p50 to raw"] is Verdict.NOT_MEASURED


def test_a_benchmark_that_failed_in_both_runs_is_still_flagged_with_its_reason(tmp_path, capsys):
    failed = {"bench_gateway_ws": {"seconds": 6.5, "failure": "the run started no gateway process", "figures": []}}
    old, new = results(tmp_path, "old", failed), results(tmp_path, "new", failed)
    assert bench_compare.main([str(old), str(new)]) == 1
    assert "NOT MEASURED: bench_gateway_ws (failed: the run started no gateway process)" in capsys.readouterr().out


def test_a_benchmark_left_out_of_the_new_run_is_not_flagged(tmp_path):
    old = {"bench_bus": bus(100.0, 1.5), "bench_sim": {"seconds": 1.0, "failure": None, "figures": [
        figure("1 stacks: simulator CPU", 90.0, "ms per simulated s")]}}
    assert verdicts(tmp_path, old, {"bench_bus": bus(100.0, 1.5)})["1 stacks: simulator CPU"] is Verdict.NOT_RUN


@pytest.mark.parametrize("content, reason", [
    ("not json", "not a results file"),
    (json.dumps({"format": 7}), "not a results file of format 1"),
    (json.dumps({"format": 1, "commit": {"sha": "x", "dirty": False}}), "missing or misspelling 'machine'"),
])
def test_a_file_that_is_not_a_results_file_is_refused_in_one_line_with_exit_2(tmp_path, content, reason):
    bad = tmp_path / "bad.json"
    bad.write_text(content)
    good = results(tmp_path, "good", {"bench_bus": bus(100.0, 1.5)})
    completed = subprocess.run([sys.executable, "-m", "bench.compare", str(good), str(bad)], cwd=REPO,
                               capture_output=True, text=True)
    assert completed.returncode == 2 and completed.stdout == ""
    assert completed.stderr.count("\n") == 1 and reason in completed.stderr, completed.stderr


def test_quick_and_full_sizes_are_refused_as_not_comparable(tmp_path, capsys):
    quick = results(tmp_path, "quick", {"bench_bus": bus(100.0, 1.5)}, quick=True)
    full = results(tmp_path, "full", {"bench_bus": bus(100.0, 1.5)})
    assert bench_compare.main([str(quick), str(full)]) == 2
    assert "quick sizes" in capsys.readouterr().err


def world_parts(by_time: float, by_instructions: float | None) -> dict:
    """bench_world_parts as the runner writes it: a speed-up in time, guarded by the same in instructions."""
    counted = "intersection: speed-up, instructions"
    figures = [{**figure("intersection: speed-up", by_time, "ratio", "general path", "higher"), "guarded_by": counted}]
    if by_instructions is not None:
        figures.append(figure(counted, by_instructions, "ratio", "general path, instructions", "higher"))
    return {"seconds": 60.0, "failure": None, "figures": figures}


def test_a_time_ratio_guarded_by_its_instruction_count_is_flagged_only_through_the_count(tmp_path):
    # The turn-about speed-up moved from 21.1 to 14.0 between two quiet runs of one commit; the count did not.
    assert verdicts(tmp_path, {"bench_world_parts": world_parts(21.1, 12.3)},
                    {"bench_world_parts": world_parts(14.0, 12.3)}) == {
        "intersection: speed-up": Verdict.WORSE_IN_TIME, "intersection: speed-up, instructions": Verdict.WITHIN_NOISE}
    assert verdicts(tmp_path, {"bench_world_parts": world_parts(21.1, 12.3)},
                    {"bench_world_parts": world_parts(14.0, 9.0)}) == {
        "intersection: speed-up": Verdict.WORSE_IN_TIME, "intersection: speed-up, instructions": Verdict.WORSE}


def test_a_guarded_time_ratio_whose_count_is_missing_is_flagged_by_itself(tmp_path):
    assert verdicts(tmp_path, {"bench_world_parts": world_parts(21.1, 12.3)},
                    {"bench_world_parts": world_parts(14.0, None)})["intersection: speed-up"] is Verdict.WORSE


def test_ratios_with_neither_an_interval_nor_an_instruction_count_are_named_after_the_comparison(tmp_path, capsys):
    with_interval = {**figure("scene: association to brute force", 0.02, "ratio", "brute force"), "spread": 0.2}
    new = {"bench_bus": bus(100.0, 1.5), "bench_world_parts": world_parts(21.1, 12.3),
           "bench_scene": {"seconds": 5.0, "failure": None, "figures": [with_interval]}}
    old_path, new_path = results(tmp_path, "old", new), results(tmp_path, "new", new)
    assert bench_compare.unguarded_ratios(BenchResults.load(new_path)) == [("bench_bus", "coopdrive typed p50 to raw")]
    assert bench_compare.main([str(old_path), str(new_path)]) == 0
    assert "1 ratios of NEW have neither an interval nor an instruction count" in capsys.readouterr().out
