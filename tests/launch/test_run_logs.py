"""`coopdrive run ... --logs DIR`: one log per service process, at INFO, so a user sees why things happened."""

import subprocess
import sys


def test_the_planner_s_log_names_its_transitions_with_their_reasons(tmp_path):
    completed = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "follow", "--duration", "3", "--logs",
                                str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert completed.returncode in (0, 1), completed.stderr[-2000:]
    assert {"ego-geolocation.log", "ego-planner.log", "ego-control.log", "world-sim.log"} <= {
        path.name for path in tmp_path.iterdir()}
    planner_log = (tmp_path / "ego-planner.log").read_text()
    assert "INFO" in planner_log and "on START: machine started" in planner_log
