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


def tiny_string(followers: int, duration_s: float, string_end_s: float | None = None) -> str:
    """The string scenario made small: a scripted leader oscillating 0.2 Hz +-10 km/h from 1 s and `followers` stacks
    behind it, started as a platoon at 0.2 s and judged from 2 s (to string_end_s): the smallest runs with a string
    gain."""
    vehicles = "\n".join(f"  - {{vehicle_id: f{index}, station_id: {501 + index}, lane: 0, "
                         f"station_m: {300 - 22 * index}, speed_mps: 22.2, platoon: 1}}"
                         for index in range(1, followers + 1))
    platoon = ", ".join(["leader"] + [f"f{index}" for index in range(1, followers + 1)])
    end = "" if string_end_s is None else f"\n  string_end_s: {string_end_s}"
    return f"""
name: tiny_string
mission: platoon
map: a270
duration_s: {duration_s}
vehicles:
  - {{vehicle_id: leader, station_id: 501, role: scripted, lane: 0, station_m: 300, speed_mps: 22.2,
     speed_profile: {{kind: sinusoid, mean_speed_mps: 22.2, amplitude_mps: 2.78, frequency_hz: 0.2, start_s: 1}}}}
{vehicles}
roadside_units:
  - {{unit_id: rsu, station_id: 590, x_m: 250, y_m: 30,
     events: [{{kind: start_platoon, time_s: 0.2, until_s: 4, platoon: 0}}]}}
judging:
  platoon: [{platoon}]
  headway_s: 0.5
  string_start_s: 2
  string_frequency_hz: 0.2{end}
"""
