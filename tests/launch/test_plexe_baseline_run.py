"""`coopdrive run SCENARIO --baseline sumo-plexe`: our run, then its platoon under Plexe's PLOEG in SUMO, both
string gains per pair printed, and the exit status says whether ours damps at least as well."""

import re
import subprocess
import sys

import pytest

from coopdrive.cli import main
from coopdrive.exit_status import EXIT_USAGE
from tests.scenario_report import FASTEST_LAYOUT, tiny_string

pytestmark = pytest.mark.whole_run

# Two stacks behind the oscillating leader, judged over one period (2 s to 7 s): the shortest run with a gain per
# pair.
SHORT_STRING = tiny_string(followers=2, duration_s=8, string_end_s=7)
# A row of the comparison's table: the metric, ours, Plexe's.
ROW = re.compile(r"^\W*(string_gain\w*)\W+([0-9.]+)\W+([0-9.]+)\W*$", re.MULTILINE)


def test_run_with_the_plexe_baseline_prints_both_gains_per_pair_and_passes_only_if_ours_is_no_worse(tmp_path):
    scenario = tmp_path / "tiny_string.yaml"
    scenario.write_text(SHORT_STRING)
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(scenario), "--baseline",
                                "sumo-plexe", *FASTEST_LAYOUT], capture_output=True, text=True, timeout=300)
    assert completed.returncode in (0, 1), completed.stderr
    assert "Plexe's PLOEG CACC in SUMO" in " ".join(completed.stdout.split())
    rows = {metric: (float(ours), float(plexe)) for metric, ours, plexe in ROW.findall(completed.stdout)}
    assert set(rows) == {"string_gain", "string_gain_pair_1", "string_gain_pair_2"}
    assert all(0.0 < gain < 2.0 for pair in rows.values() for gain in pair)
    ours, plexe = rows["string_gain"]
    assert ours == max(rows["string_gain_pair_1"][0], rows["string_gain_pair_2"][0])
    assert plexe == max(rows["string_gain_pair_1"][1], rows["string_gain_pair_2"][1])
    assert (completed.returncode == 0) == (ours <= plexe)


def test_without_libsumo_the_plexe_baseline_is_refused_in_one_line_before_anything_starts(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "libsumo", None)
    assert main(["run", "string", "--baseline", "sumo-plexe"]) == EXIT_USAGE
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "libsumo" in error and "not installed" in error


def test_a_scenario_without_a_judged_platoon_has_no_plexe_baseline(tmp_path, capsys):
    scenario = tmp_path / "alone.yaml"
    scenario.write_text(
        "name: alone\nmission: platoon\nmap: a270\nduration_s: 5\n"
        "vehicles:\n  - {vehicle_id: ego, station_id: 1, lane: 0, station_m: 300, speed_mps: 20}\n")
    assert main(["run", str(scenario), "--baseline", "sumo-plexe"]) == EXIT_USAGE
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "judging.platoon" in error
