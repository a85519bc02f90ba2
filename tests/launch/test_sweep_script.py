"""tools/sweep.sh, the committed script that runs issue 26's sweep: it prints the pass table it wrote and its exit
status says whether every run passed, so a script or CI calling it cannot miss a failure."""

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tools" / "sweep.sh"
# One follow run (60 s simulated) on a one-worker local Dask cluster.
SWEEP_TIMEOUT_S = 300


def sweep(out: Path, **settings: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHON": sys.executable, "OUT": str(out), **settings}
    return subprocess.run(["bash", str(SCRIPT)], capture_output=True, text=True, env=env, timeout=SWEEP_TIMEOUT_S)


def test_the_script_sweeps_a_scenario_s_seeds_prints_the_pass_table_and_exits_0(tmp_path):
    """As CI calls it (.ci/run): REPORTS=0, each run's metrics and the summaries without a report."""
    result = sweep(tmp_path / "sweep", SCENARIO="follow", SEEDS="1", WORKERS="1", REPORTS="0")
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    assert "| follow | none | 1/1 | pass |" in result.stdout
    assert (tmp_path / "sweep" / "pass_table.md").read_text() in result.stdout
    assert (tmp_path / "sweep" / "summary.json").is_file()
    run_folder = tmp_path / "sweep" / "follow" / "none" / "seed-1"
    assert [path.name for path in run_folder.iterdir()] == ["metrics.json"]


def test_a_sweep_that_cannot_start_exits_non_zero_and_prints_no_earlier_table(tmp_path):
    out = tmp_path / "sweep"
    out.mkdir()
    (out / "pass_table.md").write_text("| an earlier sweep's table |\n")
    result = sweep(out, SCENARIO="no_such_scenario", SEEDS="1", WORKERS="1")
    assert result.returncode != 0
    assert "no_such_scenario" in result.stderr
    assert "an earlier sweep's table" not in result.stdout
