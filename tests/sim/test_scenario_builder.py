from pathlib import Path

import pytest

from coopdrive.services.sim.participants import ScriptedVehicle
from coopdrive.services.sim.profiles import TRUCK
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import load_scenario, parse_scenario

roadmap = pytest.importorskip("coopdrive.roadmap")
EXAMPLE = Path(__file__).resolve().parents[2] / "services" / "sim" / "examples" / "string_stability.yaml"


def test_the_example_scenario_builds_models_sensors_and_participants_on_the_a270():
    objects = build_scenario(load_scenario(EXAMPLE), roadmap.RoadMap.load("a270"))
    assert set(objects.models) == {"ego", "f2", "truck"} and set(objects.sensor_suites) == set(objects.models)
    assert isinstance(objects.participants["leader"], ScriptedVehicle)
    assert objects.models["truck"].profile == TRUCK
    assert objects.models["ego"].state.speed_mps == pytest.approx(11.1)
    assert len(objects.roadside_units) == 1 and objects.roadside_units[0].messages_due(1.0)


def test_a_lane_missing_from_the_map_is_named():
    config = parse_scenario({"name": "x", "duration_s": 1, "vehicles": [
        {"vehicle_id": "a", "station_id": 1, "lane": 7, "station_m": 0, "speed_mps": 1}]})
    with pytest.raises(ValueError, match="vehicle a: road 'a270' has no lane 7"):
        build_scenario(config, roadmap.RoadMap.load("a270"))
