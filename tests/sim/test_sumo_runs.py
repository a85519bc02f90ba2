"""`coopdrive run` and `replay` on SUMO networks. The follow scenario end to end on a network that netgenerate built
at test time and that is laid in Sweden by its projection: the stack follows and passes, and where it says it is, in
latitude and longitude, is on SUMO's lane by SUMO's own projection (sumolib's convertLonLat2XY), as are the leader's
CAM positions, and Foxglove's channels draw them there. Its recording replays on the same network, and says so in
one line where the network is not. A network that cannot be a map, or no sumolib: one line, and nothing starts."""

import json
import subprocess
import sys

import numpy as np
import pytest
import sumolib

from coopdrive.recording.reader import read_messages
from tests.scenario_report import FASTEST_LAYOUT
from tests.sumo_networks import (ASTAZERO_LAT_LON_DEG, follow_scenario, geo_referenced, scenario_file,
                                 straight_road, with_roads)
from tests.visual.foxglove_mcap import foxglove_channels

pytestmark = pytest.mark.whole_run

DURATION_S = 20.0
# The eastbound edge's rightmost lane, where both vehicles drive: its centre line in the network's coordinates.
LANE_ID = "A0B0_0"
LANE_CENTRE_Y_M = -5.25
LEADER_STATION_ID = 1001


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sumo_follow")
    network = geo_referenced(straight_road(folder / "astazero.net.xml"), *ASTAZERO_LAT_LON_DEG)
    scenario = folder / "sumo-follow.yaml"
    scenario.write_text(follow_scenario(network.name, DURATION_S))
    recording = folder / "run.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", str(scenario), "--json", "--record",
                             str(recording), *FASTEST_LAYOUT], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads(result.stdout), recording, sumolib.net.readNet(str(network))


def coopdrive(*args: str):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=300)


def on_the_lane_m(net, lat_deg: float, lon_deg: float) -> tuple[float, float]:
    """(x_m along the road, offset from the lane's centre) of a geodetic point in the network's coordinates."""
    x_m, y_m = net.convertLonLat2XY(lon_deg, lat_deg)
    return x_m, y_m - LANE_CENTRE_Y_M


def test_the_stack_follows_the_leader_on_the_sumo_network_and_passes(run):
    summary, _, _ = run
    assert summary["scenario"] == "sumo-follow" and summary["sim_time_s"] == pytest.approx(DURATION_S)
    assert summary["success"] is True and summary["collisions"] == 0
    assert summary["min_gap_m"] > 6.0


def test_the_stack_s_latitude_and_longitude_lie_on_sumo_s_lane_by_sumo_s_projection(run):
    _, recording, net = run
    states = [item.message for item in read_messages(recording) if item.topic == "coopdrive/ego/ego/state"]
    matched = [state for state in states if state.lane.matched]
    assert len(matched) > 0.9 * len(states)
    assert {state.lane.lane_id for state in matched} == {LANE_ID}
    along_m, offset_m = np.array([on_the_lane_m(net, s.latitude_deg, s.longitude_deg) for s in matched]).T
    # The stack keeps to its lane's centre (centimetres here); a frame off by the projection would be metres off.
    assert np.max(np.abs(offset_m)) < 0.5
    assert along_m[-1] - along_m[0] > 10.0 * DURATION_S


def test_the_leader_s_cam_positions_lie_on_sumo_s_lane_too(run):
    _, recording, net = run
    cams = [item.message for item in read_messages(recording) if item.topic == "coopdrive/ego/v2x/cam"
            and item.message.station_id == LEADER_STATION_ID]
    assert cams
    offset_m = np.array([on_the_lane_m(net, cam.reference_position.latitude_deg,
                                       cam.reference_position.longitude_deg)[1] for cam in cams])
    assert np.max(np.abs(offset_m)) < 0.5



def test_the_recording_draws_the_network_s_lanes_and_the_stack_on_them_for_foxglove(run):
    _, recording, net = run
    channels = foxglove_channels(recording)
    # The lane map, drawn again every second for a viewer that joins late.
    assert len(channels["foxglove/map"]) >= DURATION_S
    for lanes in channels["foxglove/map"]:
        assert sorted(entity.id for entity in lanes.entities) == [f"lane/{edge}_{index}" for edge in ("A0B0", "B0A0")
                                                                  for index in range(2)]
    fixes = channels["foxglove/ego/ego"]
    assert fixes
    assert max(abs(on_the_lane_m(net, fix.latitude, fix.longitude)[1]) for fix in fixes) < 0.5


def test_the_run_s_geolocation_replays_over_its_recording_on_the_same_network(run, tmp_path):
    _, recording, _ = run
    result = coopdrive("replay", str(recording), "--service", "geolocation", "--out", str(tmp_path / "replayed.mcap"),
                       "--json")
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["counters"]["accepted_gnss_position"] > 0


def test_replaying_the_run_where_its_network_is_not_says_so_in_one_line(run, tmp_path):
    _, recording, _ = run
    network = recording.parent / "astazero.net.xml"
    network.rename(tmp_path / network.name)
    try:
        result = coopdrive("replay", str(recording), "--service", "control", "--out", str(tmp_path / "replayed.mcap"))
    finally:
        (tmp_path / network.name).rename(network)
    assert result.returncode == 2
    assert result.stderr == f"coopdrive: replay: {recording}: its map: {network}: no such SUMO network file\n"


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return with_roads(tmp_path_factory.mktemp("sumo_refused"))


@pytest.mark.parametrize("map_text", ["roads/nowhere.net.xml", "roads/routes.rou.xml", "roads/footpaths.net.xml"],
                         ids=["missing", "routes", "footpaths"])
def test_coopdrive_run_on_a_network_that_cannot_be_a_map_says_so_in_one_line_and_starts_nothing(folder, map_text):
    result = coopdrive("run", str(scenario_file(folder, map_text, "bad.yaml")))
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
