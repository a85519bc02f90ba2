"""A scenario file that names a SUMO network as its map: found from the file's folder, built against the network's
lanes, and refused in one line when the network cannot be a map (tests/sim/test_sumo_runs.py: by `coopdrive run`,
before anything starts)."""

import pytest

from coopdrive.launch.scenario_source import resolve_scenario
from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import ScenarioError, load_scenario
from tests.sumo_networks import scenario_file, with_roads


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return with_roads(tmp_path_factory.mktemp("sumo_scenario"))


def test_a_network_named_relative_to_the_scenario_file_is_found_from_its_folder_and_held_absolute(folder):
    config = load_scenario(scenario_file(folder, "roads/straight.net.xml", "follow.yaml"))
    assert config.map == str((folder / "roads" / "straight.net.xml").resolve())


def test_the_scenario_s_vehicles_are_placed_on_the_network_s_edge_and_lane(folder):
    config = load_scenario(scenario_file(folder, "roads/straight.net.xml", "follow.yaml"))
    objects = build_scenario(config, RoadMap.load(config.map))
    assert [lane.lane_id for lane in objects.lanes["ego"]] == ["A0B0_0", "A0B0_1"]
    assert (objects.models["ego"].state.x_m, objects.models["ego"].state.y_m) == pytest.approx((0.0, -5.25))


def test_a_run_with_faults_added_keeps_finding_the_network_from_its_copy_in_another_folder(folder, tmp_path):
    source = resolve_scenario(str(scenario_file(folder, "roads/straight.net.xml", "follow.yaml")))
    copy = source.with_faults([{"type": "v2v_loss", "vehicle_id": "ego", "start_s": 1, "loss_probability": 0.5}],
                              tmp_path)
    assert copy.file.parent == tmp_path
    assert copy.config.map == source.config.map


def test_a_run_with_faults_added_keeps_finding_sumo_s_traffic_from_its_copy_in_another_folder(tmp_path):
    source = resolve_scenario("sumo-motorway")
    copy = source.with_faults([{"type": "v2v_loss", "start_s": 1, "loss_probability": 0.5}], tmp_path)
    assert copy.file.parent == tmp_path
    assert copy.config.sumo_traffic == source.config.sumo_traffic
    assert [v.station_m for v in copy.config.vehicles] == [v.station_m for v in source.config.vehicles]


@pytest.mark.parametrize("map_text, problem", [
    ("roads/nowhere.net.xml", "no such SUMO network file"),
    ("roads/routes.rou.xml", "not a SUMO network (its root element is <routes>, not <net>)"),
    ("roads/footpaths.net.xml", "the SUMO network has no drivable lane (8 lanes, none that a passenger car may use)"),
], ids=["missing", "routes", "footpaths"])
def test_a_network_that_cannot_be_a_map_is_one_line_naming_the_file_and_the_problem(folder, map_text, problem):
    scenario = scenario_file(folder, map_text, "bad.yaml")
    with pytest.raises(ScenarioError) as error:
        load_scenario(scenario)
    network = (folder / map_text).resolve()
    assert str(error.value) == f"{scenario}: map: {network}: {problem}"
