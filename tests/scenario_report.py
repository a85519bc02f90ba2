"""Runs a packaged scenario the way a user would, `coopdrive run NAME --report DIR`, and reads its metrics.json."""

import json
import subprocess
import sys
from pathlib import Path

RUN_TIMEOUT_S = 900


def run_scenario_report(folder: Path, scenario: str, duration_s: float, world: str = "real",
                        extra: tuple[str, ...] = ()) -> dict:
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", scenario, "--duration", str(duration_s),
                             "--world", world, "--report", str(folder), *extra],
                            capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads((folder / "metrics.json").read_text())
