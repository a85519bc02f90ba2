"""tools/sweep.sh, the committed script that runs issue 26's sweep: it prints the pass table it wrote and its exit
status says whether every run passed, so a script or CI calling it cannot miss a failure; and tools/ci_sweep.sh,
CI's call of it in the time CI has left."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.whole_run

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tools" / "sweep.sh"
# One follow run (DURATION_S simulated) on a one-worker local Dask cluster.
SWEEP_TIMEOUT_S = 300
DURATION_S = 5


def sweep(out: Path, **settings: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHON": sys.executable, "OUT": str(out), **settings}
    return subprocess.run(["bash", str(SCRIPT)], capture_output=True, text=True, env=env, timeout=SWEEP_TIMEOUT_S)


def test_the_script_sweeps_a_scenario_s_seeds_prints_the_pass_table_and_exits_0(tmp_path):
    """As CI calls it (tools/ci_sweep.sh): REPORTS=0, each run's metrics and the summaries without a report."""
    result = sweep(tmp_path / "sweep", SCENARIO="follow", SEEDS="1", WORKERS="1", REPORTS="0",
                   DURATION=str(DURATION_S))
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


CI_SCRIPT = REPO / "tools" / "ci_sweep.sh"


def with_stand_in(tmp_path: Path, command: list[str], sweep_status: int,
                  **settings: str) -> tuple[subprocess.CompletedProcess, str]:
    """Runs a script with a stand-in for the sweep's interpreter that records its arguments and exits with
    sweep_status, as `coopdrive run all` would."""
    arguments = tmp_path / "arguments"
    stand_in = tmp_path / "python"
    stand_in.write_text(f'#!/bin/sh\necho "$@" > {arguments}\nexit {sweep_status}\n')
    stand_in.chmod(0o755)
    env = {**os.environ, "PYTHON": str(stand_in), "OUT": str(tmp_path / "sweep"), **settings}
    result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=60)
    return result, arguments.read_text() if arguments.exists() else ""


def ci_sweep(tmp_path: Path, seconds_left: int, sweep_status: int) -> tuple[subprocess.CompletedProcess, str]:
    return with_stand_in(tmp_path, ["bash", str(CI_SCRIPT), str(seconds_left)], sweep_status)


def test_duration_runs_every_scenario_that_long_and_without_it_each_runs_its_own(tmp_path):
    _, arguments = with_stand_in(tmp_path, ["bash", str(SCRIPT)], 0, DURATION="5")
    assert "--duration 5" in arguments
    _, arguments = with_stand_in(tmp_path, ["bash", str(SCRIPT)], 0)
    assert "--duration" not in arguments


def test_ci_sweeps_seeds_1_and_2_of_every_scenario_without_reports_in_the_seconds_it_has_left(tmp_path):
    result, arguments = ci_sweep(tmp_path, 480, 0)
    assert result.returncode == 0
    assert arguments.split()[:7] == ["-m", "coopdrive.cli", "run", "all", "--seeds", "1-2", "--workers"]
    assert "--no-reports" in arguments and "--time-limit 480" in arguments


def test_a_failed_run_fails_ci_and_runs_the_time_did_not_reach_do_not(tmp_path):
    failed, _ = ci_sweep(tmp_path, 480, 1)
    assert failed.returncode == 1
    stopped, _ = ci_sweep(tmp_path, 480, 4)
    assert stopped.returncode == 0
    assert "CI sweep: stopped after 480 s with runs not finished" in stopped.stdout


def test_with_under_a_minute_left_ci_skips_the_sweep_and_says_so(tmp_path):
    result, arguments = ci_sweep(tmp_path, 40, 0)
    assert result.returncode == 0 and arguments == ""
    assert result.stdout == "CI sweep skipped: 40 s of CI's time left\n"


NICE_RECORDER = """#!/bin/sh
policy=$(chrt -p $$ | head -1 | sed 's/.*: //')
echo "$policy $COOPDRIVE_SESSION_NICE $(nice) $(cat /proc/self/autogroup 2>/dev/null)" > {record}
exit 0
"""


def test_beside_the_suite_the_sweep_runs_as_an_idle_task_and_its_session_and_every_session_its_runs_start_at_nice_19(
        tmp_path):
    record = tmp_path / "record"
    stand_in = tmp_path / "python"
    stand_in.write_text(NICE_RECORDER.format(record=record))
    stand_in.chmod(0o755)
    env = {**os.environ, "PYTHON": str(stand_in), "OUT": str(tmp_path / "sweep"), "BESIDE": "1"}
    result = subprocess.run(["bash", str(CI_SCRIPT), "480"], capture_output=True, text=True, env=env, timeout=60,
                            start_new_session=True)
    assert result.returncode == 0, result.stderr
    policy, session_nice, thread_nice, *autogroup = record.read_text().split()
    assert (policy, session_nice, thread_nice) == ("SCHED_IDLE", "19", "19")
    if Path("/proc/self/autogroup").exists():
        assert autogroup[1:] == ["nice", "19"]


def test_beside_the_suite_the_sweep_refuses_to_lower_a_session_it_does_not_lead(tmp_path):
    result, arguments = with_stand_in(tmp_path, ["bash", str(CI_SCRIPT), "480"], 0, BESIDE="1")
    assert result.returncode == 2 and arguments == ""
    assert result.stderr == ("tools/ci_sweep.sh: BESIDE=1 lowers its whole session's priority, so it must lead one of "
                             "its own (setsid)\n")
