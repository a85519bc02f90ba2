from pathlib import Path

import pytest
import yaml

from coopdrive import roadmap
from coopdrive.services.sim.roadside_unit import RsuEventKind
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import ScenarioError, VehicleRole, load_scenario

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"
FILES = sorted(SCENARIOS.glob("*.yaml"))


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_every_scenario_file_loads_and_builds_against_its_map(path):
    config = load_scenario(path)
    objects = build_scenario(config, roadmap.RoadMap.load(config.map))
    assert set(objects.lanes) == {v.vehicle_id for v in config.vehicles}
    assert config.description


def test_the_merge_scenario_announces_road_works():
    config = load_scenario(SCENARIOS / "merge.yaml")
    kinds = [e.kind for unit in config.roadside_units for e in unit.events]
    assert RsuEventKind.ROADWORKS in kinds


def test_the_emergency_scenario_has_an_emergency_vehicle():
    config = load_scenario(SCENARIOS / "emergency.yaml")
    assert any(v.role is VehicleRole.EMERGENCY for v in config.vehicles)


def test_the_string_leader_oscillates_at_0_2_hz():
    config = load_scenario(SCENARIOS / "string.yaml")
    leader = next(v for v in config.vehicles if v.vehicle_id == config.judging.platoon[0])
    assert leader.speed_profile.frequency_hz == pytest.approx(0.2)
    assert config.judging.string_frequency_hz == pytest.approx(0.2)


def test_a_bad_key_gives_one_error_line_naming_it(tmp_path):
    data = yaml.safe_load((SCENARIOS / "string.yaml").read_text())
    data["vehicles"][1]["spede_mps"] = 3.0
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(data))
    with pytest.raises(ScenarioError) as error:
        load_scenario(bad)
    assert "spede_mps" in str(error.value)
    assert "\n" not in str(error.value)
