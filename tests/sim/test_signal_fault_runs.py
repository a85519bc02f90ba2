"""`coopdrive run` of one stack up to the second crossroads of the signals corridor, on its green, with each fault
of its roadside unit (a SPaT lost, a SPaT whose timing jumps, a MAP whose lanes lie off the road): the run passes,
no light is run, and the verdict names the stack's safe reaction (services/sim/signal_fault_reactions.py)."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

pytestmark = pytest.mark.whole_run

SIGNALS = Path(__file__).parents[2] / "scenarios" / "signals.yaml"
# 100 m before the second crossroads' stop line (station 690) at 50 km/h: its main road is green until 20 s, and the
# stack would cross at about 7 s.
START_STATION_M = 590
SPEED_MPS = 13.9
DURATION_S = 20
FAULT_START_S, FAULT_END_S = 2.0, 13.0
GREEN = "protected movement allowed"


def run_with(fault: dict, tmp_path: Path) -> dict:
    scenario = yaml.safe_load(SIGNALS.read_text(encoding="utf-8"))
    scenario["vehicles"] = [dict(scenario["vehicles"][0], station_m=START_STATION_M)]
    scenario["judging"] = {"platoon": ["car1"]}
    path = tmp_path / "signals_second_crossroads.yaml"
    path.write_text(yaml.safe_dump(scenario), encoding="utf-8")
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(path), "--stacks", "1", "--duration",
                             str(DURATION_S), "--json", "--fault", json.dumps(fault)],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    summary = json.loads(result.stdout)
    assert summary["success"] is True and summary["collisions"] == 0, summary
    assert summary["signal_red_light_violations"] == 0
    return summary


def stopped_on_green_then_crossed(reaction: str, fault: str) -> re.Match | None:
    return re.fullmatch(rf"{re.escape(fault)}: car1 stopped (?P<before_m>[\d.]+) m before the stop line of "
                        rf"intersection 2 at (?P<stood_s>[\d.]+) s \({GREEN}\), crossed at (?P<crossed_s>[\d.]+) s "
                        rf"\((?P<margin_s>[\d.]+) s before red\)", reaction)


def test_a_stack_whose_spat_is_lost_on_its_green_stops_at_the_line_and_goes_when_the_spat_is_back(tmp_path):
    summary = run_with({"type": "spat_loss", "unit_id": "rsu_b", "start_s": FAULT_START_S, "end_s": FAULT_END_S},
                       tmp_path)
    [reaction] = summary["fault_reactions"]
    found = stopped_on_green_then_crossed(reaction, f"spat_loss at rsu_b ({FAULT_START_S}-{FAULT_END_S} s)")
    assert found, reaction
    assert float(found["before_m"]) < 5.0 and float(found["crossed_s"]) > FAULT_END_S


def test_a_stack_on_no_lane_of_a_map_moved_off_the_road_stops_at_the_line_and_goes_when_the_map_is_right(tmp_path):
    summary = run_with({"type": "map_lane_offset", "unit_id": "rsu_b", "north_m": 3.5, "start_s": FAULT_START_S,
                        "end_s": FAULT_END_S}, tmp_path)
    [reaction] = summary["fault_reactions"]
    found = stopped_on_green_then_crossed(reaction, f"map_lane_offset at rsu_b ({FAULT_START_S}-{FAULT_END_S} s)")
    assert found, reaction
    assert float(found["before_m"]) < 5.0 and float(found["crossed_s"]) > FAULT_END_S


def test_a_stack_whose_spat_timing_jumps_on_its_green_slows_while_it_contradicts_itself_and_crosses_on_green(
        tmp_path):
    """The jump (every stated end 10 s later) contradicts the SPaT before it: the stack brakes towards the line for
    the contradiction's hold (5 s), then trusts the SPaT again, whose lights are right, and crosses on green."""
    summary = run_with({"type": "spat_time_jump", "unit_id": "rsu_b", "jump_s": 10.0, "start_s": FAULT_START_S},
                       tmp_path)
    [reaction] = summary["fault_reactions"]
    found = re.fullmatch(rf"spat_time_jump at rsu_b \({FAULT_START_S}-inf s\): car1 crossed the stop line of "
                         rf"intersection 2 at (?P<crossed_s>[\d.]+) s without stopping \(slowest "
                         rf"(?P<slowest_mps>[\d.]+) m/s, (?P<margin_s>[\d.]+) s before red\)", reaction)
    assert found, reaction
    assert float(found["slowest_mps"]) < 0.5 * SPEED_MPS
