import copy
from pathlib import Path

import pytest

from coopdrive.services.sim.fault_config import FixDowngrade, V2vLoss
from coopdrive.vehicle import VehicleKind
from coopdrive.services.sim.scenario_config import ScenarioError, load_scenario, parse_scenario
from coopdrive.services.sim.sensor_config import FixModeName
from coopdrive.services.sim.speed_profiles import SinusoidSpeed

EXAMPLE = Path(__file__).resolve().parents[2] / "services" / "sim" / "examples" / "string_stability.yaml"
BASE = {
    "name": "t", "duration_s": 10.0,
    "vehicles": [{"vehicle_id": "a", "station_id": 1, "lane": 0, "station_m": 50.0, "speed_mps": 10.0},
                 {"vehicle_id": "b", "station_id": 2, "lane": 0, "station_m": 20.0, "speed_mps": 10.0}],
}


def _error_of(change):
    data = copy.deepcopy(BASE)
    change(data)
    with pytest.raises(ScenarioError) as caught:
        parse_scenario(data, "scenarios/x.yaml")
    message = str(caught.value)
    assert "\n" not in message
    return message


def test_the_example_scenario_loads_with_its_profiles_and_faults():
    scenario = load_scenario(EXAMPLE)
    assert scenario.vehicles[3].profile is VehicleKind.TRUCK
    assert isinstance(scenario.vehicles[0].speed_profile, SinusoidSpeed)
    assert isinstance(scenario.faults[0], FixDowngrade) and scenario.faults[0].fix_mode is FixModeName.SBAS
    assert isinstance(scenario.faults[1], V2vLoss) and scenario.faults[1].active(42.0)
    assert scenario.sensors_of(scenario.vehicles[1]).radar.range_sigma_m == 0.3


def test_a_malformed_scenario_gives_one_error_line_naming_the_key():
    message = _error_of(lambda d: d["vehicles"][1].update(speed_mps="fast"))
    assert message.startswith("scenarios/x.yaml: vehicles.1.speed_mps: Input should be a valid number")


def test_an_unknown_key_is_refused_with_its_path():
    message = _error_of(lambda d: d["vehicles"][0].update(colour="red"))
    assert message.startswith("scenarios/x.yaml: vehicles.0.colour: Extra inputs are not permitted")


def test_errors_inside_tagged_unions_name_the_key_without_the_tag():
    message = _error_of(lambda d: d.update(faults=[{"type": "fix_downgrade", "vehicle_id": "a", "start_s": 1,
                                                    "fix_mode": "perfect"}]))
    assert message.startswith("scenarios/x.yaml: faults.0.fix_mode: Input should be")
    message = _error_of(lambda d: d["vehicles"][0].update(speed_profile={"kind": "sinusoid", "mean_speed_mps": 3,
                                                                         "amplitude_mps": 1}))
    assert message.startswith("scenarios/x.yaml: vehicles.0.speed_profile.frequency_hz: Field required")


def test_references_to_unknown_vehicles_and_duplicate_ids_are_refused():
    message = _error_of(lambda d: d.update(faults=[{"type": "gnss_outage", "vehicle_id": "zz", "start_s": 1}]))
    assert message == "scenarios/x.yaml: faults.0.vehicle_id: unknown vehicle 'zz'"
    message = _error_of(lambda d: d["vehicles"][1].update(vehicle_id="a"))
    assert message == "scenarios/x.yaml: vehicles.1.vehicle_id: duplicate vehicle_id 'a'"


def test_several_errors_still_make_one_line():
    message = _error_of(lambda d: d.update(duration_s=-1, step_s=0))
    assert message.startswith("scenarios/x.yaml: duration_s: Input should be greater than 0 (and 1 more error)")


def test_unreadable_and_invalid_yaml_files_give_one_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: [unclosed\n")
    with pytest.raises(ScenarioError, match=r"bad.yaml: invalid YAML at line \d+"):
        load_scenario(bad)
    with pytest.raises(ScenarioError, match="missing.yaml: cannot read"):
        load_scenario(tmp_path / "missing.yaml")
