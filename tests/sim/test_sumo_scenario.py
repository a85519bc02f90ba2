"""A scenario file that names a SUMO network as its map: found from the file's folder, built against the network's
lanes, and refused in one line, before anything starts, when the network cannot be a map."""

import subprocess
import sys

import pytest

from coopdrive.launch.scenario_source import resolve_scenario
from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import ScenarioError, load_scenario
from tests.sumo_networks import follow_scenario, footpaths_only, straight_road


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sumo_scenario")
    (folder / "roads").mkdir()
    straight_road(folder / "roads" / "straight.net.xml")
    footpaths_only(folder / "roads" / "footpaths.net.xml")
    (folder / "roads" / "routes.rou.xml").write_text('<routes><vehicle id="a" depart="0"/></routes>\n')
    return folder


def scenario_file(folder, map_text: str, name: str = "follow.yaml"):
    path = folder / name
    path.write_text(follow_scenario(map_text))
    return path


def coopdrive_run(scenario):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(scenario)],
                          capture_output=True, text=True, timeout=120)


def test_a_network_named_relative_to_the_scenario_file_is_found_from_its_folder_and_held_absolute(folder):
    config = load_scenario(scenario_file(folder, "roads/straight.net.xml"))
    assert config.map == str((folder / "roads" / "straight.net.xml").resolve())


def test_the_scenario_s_vehicles_are_placed_on_the_network_s_edge_and_lane(folder):
    config = load_scenario(scenario_file(folder, "roads/straight.net.xml"))
    objects = build_scenario(config, RoadMap.load(config.map))
    assert [lane.lane_id for lane in objects.lanes["ego"]] == ["A0B0_0", "A0B0_1"]
    assert (objects.models["ego"].state.x_m, objects.models["ego"].state.y_m) == pytest.approx((0.0, -5.25))


def test_a_run_with_faults_added_keeps_finding_the_network_from_its_copy_in_another_folder(folder, tmp_path):
    source = resolve_scenario(str(scenario_file(folder, "roads/straight.net.xml")))
    copy = source.with_faults([{"type": "v2v_loss", "vehicle_id": "ego", "start_s": 1, "loss_probability": 0.5}],
                              tmp_path)
    assert copy.file.parent == tmp_path
    assert copy.config.map == source.config.map


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


@pytest.mark.parametrize("map_text", ["roads/nowhere.net.xml", "roads/routes.rou.xml", "roads/footpaths.net.xml"],
                         ids=["missing", "routes", "footpaths"])
def test_coopdrive_run_on_a_network_that_cannot_be_a_map_says_so_in_one_line_and_starts_nothing(folder, map_text):
    result = coopdrive_run(scenario_file(folder, map_text, "bad.yaml"))
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and f"map: {(folder / map_text).resolve()}: " in result.stderr
    assert result.stdout == ""


def test_coopdrive_run_without_sumolib_says_in_one_line_what_to_install_and_starts_nothing(folder):
    scenario = scenario_file(folder, "roads/straight.net.xml", "no_sumolib.yaml")
    # sumolib is installed here: None in sys.modules makes `import sumolib` fail as it does where it is not, in the
    # process that then runs the command.
    result = subprocess.run([sys.executable, "-c", "import sys; sys.modules['sumolib'] = None; "
                             "from coopdrive.cli import main; sys.exit(main())", "run", str(scenario)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert result.stderr == (f"coopdrive: {scenario}: map: {(folder / 'roads' / 'straight.net.xml').resolve()}: "
                             "reading a SUMO network needs sumolib, which is not installed "
                             "(pip install 'sumolib>=1.28,<1.29')\n")
    assert result.stdout == ""
