"""Runs a packaged scenario the way a user would, `coopdrive run NAME --report DIR`, and reads its metrics.json."""

import json
import subprocess
import sys
from pathlib import Path

RUN_TIMEOUT_S = 900
# The layout for a test whose run is judged on what the stack did, not on how its processes were laid out: the
# simulator and every stack in one process, as a sweep runs them. `make test` keeps both cores busy with two test
# files, and this layout spends about a fifth less CPU than a process per vehicle (a 1-stack platoon40 run, 8 s:
# 5.1 against 6.2 CPU-s). Every layout gives the same metrics (tests/launch/test_layouts.py).
FASTEST_LAYOUT = ("--processes", "one")


def run_scenario_report(folder: Path, scenario: str, duration_s: float, world: str = "real",
                        extra: tuple[str, ...] = ()) -> dict:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", scenario, "--duration", str(duration_s),
                             "--world", world, "--report", str(folder), *FASTEST_LAYOUT, *extra],
                            capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads((folder / "metrics.json").read_text())
