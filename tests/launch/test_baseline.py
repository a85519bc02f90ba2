"""`coopdrive run SCENARIO --baseline LAW`: the same run again on a reference CACC law, compared with ours."""

import json
import subprocess
import sys

import pytest

from coopdrive.launch.baseline import BaselineComparison, with_cacc_law
from coopdrive.launch.run import RunOptions, build_specs
from coopdrive.recording.reader import read_metadata
from coopdrive.recording.writer import CONFIG_METADATA
from coopdrive.services.control.longitudinal import CaccLaw
from coopdrive.v1 import sim_pb2
from tests.scenario_report import FASTEST_LAYOUT, tiny_string

pytestmark = pytest.mark.whole_run

# A scripted leader oscillating from 1 s and one stack behind it: the smallest run with a string gain.
TINY_STRING = tiny_string(followers=1, duration_s=12)


def result(string_gain: float) -> sim_pb2.RunResult:
    run = sim_pb2.RunResult(scenario="string", seed=1, success=True)
    run.metrics["string_gain"] = string_gain
    run.metrics["min_gap_m"] = 12.0
    return run


def test_the_baseline_changes_every_stacks_cacc_law_and_nothing_else(tmp_path):
    options = RunOptions(scenario="string", stacks=2, service_overrides={"control": {"vehicle": "passenger_car"}})
    specs = build_specs(with_cacc_law(options, CaccLaw.PLOEG), tmp_path)
    controls = [spec.config for spec in specs if spec.service == "control"]
    assert len(controls) == 2
    assert all(c["cacc_law"] == "ploeg" and c["vehicle"] == "passenger_car" for c in controls)
    assert options.service_overrides == {"control": {"vehicle": "passenger_car"}}  # the caller's options are untouched


def test_ours_passes_when_it_damps_at_least_as_well_as_the_baseline():
    assert BaselineComparison.of(CaccLaw.PLOEG, result(0.80), result(0.95)).ours_no_worse
    assert BaselineComparison.of(CaccLaw.PLOEG, result(0.95), result(0.95)).ours_no_worse


def test_ours_fails_naming_both_gains_when_the_baseline_damps_better():
    comparison = BaselineComparison.of(CaccLaw.PLOEG, result(0.97), result(0.90))
    assert not comparison.ours_no_worse
    assert comparison.failure_reason() == "ours damps worse than the ploeg baseline: string_gain 0.970 > 0.900"


def test_a_run_without_a_string_gain_has_nothing_to_decide():
    no_gain = sim_pb2.RunResult(scenario="merge", success=True)
    comparison = BaselineComparison.of(CaccLaw.PLOEG, no_gain, no_gain)
    assert not comparison.decided and comparison.ours_no_worse


def test_the_comparison_lists_each_metric_for_ours_and_the_baseline():
    table = BaselineComparison.of(CaccLaw.PLOEG, result(0.8), result(0.9)).as_dict()
    assert table["law"] == "ploeg"
    assert table["metrics"]["string_gain"] == {"ours": pytest.approx(0.8), "baseline": pytest.approx(0.9)}
    assert table["metrics"]["min_gap_m"] == {"ours": 12.0, "baseline": 12.0}


def test_run_with_a_baseline_prints_both_gains_and_passes_only_if_ours_is_no_worse(tmp_path):
    scenario = tmp_path / "tiny_string.yaml"
    scenario.write_text(TINY_STRING)
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(scenario), "--baseline", "ploeg",
                                "--json", *FASTEST_LAYOUT], capture_output=True, text=True, timeout=300)
    assert completed.returncode in (0, 1), completed.stderr
    summary = json.loads(completed.stdout)
    gains = summary["baseline"]["metrics"]["string_gain"]
    assert summary["baseline"]["law"] == "ploeg"
    assert summary["baseline"]["run"]["scenario"] == "tiny_string"
    assert 0 < gains["ours"] and 0 < gains["baseline"]
    assert summary["baseline"]["ours_no_worse"] == (gains["ours"] <= gains["baseline"])
    assert summary["success"] == (completed.returncode == 0)


def test_run_with_a_cacc_law_runs_the_stack_s_controller_on_that_law(tmp_path):
    scenario, recording = tmp_path / "tiny_string.yaml", tmp_path / "run.mcap"
    scenario.write_text(TINY_STRING)
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(scenario), "--cacc-law", "ploeg",
                                "--duration", "1", "--record", str(recording)], capture_output=True, text=True,
                               timeout=120)
    assert completed.returncode in (0, 1), completed.stderr
    # The configs in a recording are those the running services reported, not those the launcher meant.
    control = json.loads(read_metadata(recording)[CONFIG_METADATA]["f1/control"])
    assert control["cacc_law"] == "ploeg"


def test_an_unknown_baseline_law_is_refused_by_name():
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "string", "--baseline", "bogus"],
                               capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2
    assert "--baseline" in completed.stderr and "bogus" in completed.stderr
