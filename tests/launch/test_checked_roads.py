"""A run whose scenario puts a vehicle or a signal approach on a road its map does not have is refused with one
line naming it, before anything starts (the simulator would otherwise stop on it at its start)."""

from pathlib import Path

import pytest
import yaml

from coopdrive.launch.run import checked_run
from coopdrive.launch.run_spec import RunSpec
from coopdrive.services.sim.scenario_config import ScenarioError

SIGNALS = Path(__file__).resolve().parents[2] / "scenarios" / "signals.yaml"


def written(tmp_path, change) -> str:
    data = yaml.safe_load(SIGNALS.read_text(encoding="utf-8"))
    change(data)
    path = tmp_path / "signals.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return str(path)


def test_a_signal_approach_on_a_road_the_map_lacks_stops_the_run_before_it_starts(tmp_path):
    def elsewhere(data):
        data["roadside_units"][1]["intersection"]["approaches"][3]["road"] = "ring_road"
    with pytest.raises(ScenarioError, match="signal approach: the map has no lane 0 on road 'ring_road'"):
        checked_run(RunSpec(scenario=written(tmp_path, elsewhere)), tmp_path)


def test_a_vehicle_on_a_lane_the_map_lacks_stops_the_run_before_it_starts(tmp_path):
    def third_lane(data):
        data["vehicles"][3]["lane"] = 2
    with pytest.raises(ScenarioError, match="vehicle west_car: road 'main_westbound' has no lane 2"):
        checked_run(RunSpec(scenario=written(tmp_path, third_lane)), tmp_path)
