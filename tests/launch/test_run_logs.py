"""`coopdrive run ... --logs DIR`: one log per process, at INFO, so a user sees why things happened."""

import subprocess
import sys

import pytest

pytestmark = pytest.mark.whole_run


def run_with_logs(tmp_path, *extra: str) -> set[str]:
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--duration", "3", "--logs",
                                str(tmp_path), *extra], capture_output=True, text=True, timeout=300)
    assert completed.returncode in (0, 1), completed.stderr[-2000:]
    return {path.name for path in tmp_path.iterdir()}


def test_the_stack_s_log_names_the_planner_s_transitions_with_their_reasons(tmp_path):
    assert run_with_logs(tmp_path) == {"ego-group.log", "world-sim.log"}
    stack_log = (tmp_path / "ego-group.log").read_text()
    assert "coopdrive.planner INFO" in stack_log and "on START: machine started" in stack_log


def test_with_a_process_per_service_each_service_has_its_own_log(tmp_path):
    assert {"ego-geolocation.log", "ego-planner.log", "ego-control.log", "world-sim.log"} <= \
        run_with_logs(tmp_path, "--processes", "service")
    assert "on START: machine started" in (tmp_path / "ego-planner.log").read_text()
