"""`coopdrive run` among SUMO's traffic: the follow scenario on a network netgenerate built at test time, with a flow of
20 SUMO cars written at test time beside it, half of them equipped. The stack follows and passes, no collision with
SUMO's cars; SUMO's cars were in the run, the stack saw some and heard the equipped ones' CAMs, and the summary says
what SUMO counted of them; the same seed gives the same metrics in one process and in a process per service. SUMO
traffic that cannot run: one line, and nothing starts."""

import json
import subprocess
import sys

import pytest

from coopdrive.launch.summary import WALL_CLOCK_KEYS
from coopdrive.recording.reader import read_messages
from coopdrive.services.sim.sumo_traffic import FIRST_SUMO_STATION_ID
from tests.scenario_report import FASTEST_LAYOUT
from tests.sumo_networks import among_traffic, flow_routes, follow_scenario, straight_road

pytestmark = pytest.mark.whole_run

DURATION_S = 8.0
SUMO_CARS = 20


def coopdrive(*args: str):
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def scenario(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sumo_traffic")
    straight_road(folder / "road.net.xml")
    # All 20 depart within the run's first half, from the road's start behind the stack and its leader, on either lane.
    flow_routes(folder / "flow.rou.xml", number=SUMO_CARS, begin_s=0.5, end_s=DURATION_S / 2.0)
    path = folder / "sumo-traffic.yaml"
    path.write_text(among_traffic(follow_scenario("road.net.xml", DURATION_S),
                                  "{routes: [flow.rou.xml], equipped_share: 0.5}"))
    return path


@pytest.fixture(scope="module")
def recorded(scenario):
    recording = scenario.parent / "run.mcap"
    result = coopdrive("run", str(scenario), "--seed", "1", "--json", "--record", str(recording), *FASTEST_LAYOUT)
    assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
    return json.loads(result.stdout), recording


@pytest.fixture(scope="module")
def summary(recorded):
    return recorded[0]


def test_the_stack_follows_among_sumo_s_cars_and_passes_without_a_collision_with_any(summary):
    assert summary["success"] is True and summary["sim_time_s"] == pytest.approx(DURATION_S)
    assert summary["collisions"] == 0 and summary["sumo_collisions_with_ours"] == 0
    # SUMO's cars close up behind ours to SUMO's own minimum gap (2.5 m), not ours.
    assert summary["min_gap_m"] > 2.0


def test_the_summary_reports_sumo_s_cars_in_the_run_and_what_sumo_counted_of_them(summary):
    # SUMO holds back a departure until it has room: most, not always all, are on the road by the end.
    assert SUMO_CARS / 2 <= summary["sumo_vehicles"] <= SUMO_CARS
    # Those that overtook the stack on the other lane passed before its camera and radar.
    assert 1 <= summary["sumo_vehicles_seen"] <= summary["sumo_vehicles"]
    assert 1 <= summary["sumo_equipped"] < summary["sumo_vehicles"]
    for key in ("sumo_emergency_braking", "sumo_emergency_stops", "sumo_collisions", "sumo_teleports"):
        assert summary[key] >= 0
    assert summary["sumo_collisions"] == 0


def test_the_stack_s_v2x_service_hears_the_cams_of_sumo_s_equipped_cars(recorded):
    summary, recording = recorded
    senders = {item.message.station_id for item in read_messages(recording) if item.topic == "coopdrive/ego/v2x/cam"}
    sumo_senders = {station_id for station_id in senders if station_id >= FIRST_SUMO_STATION_ID}
    assert 1 <= len(sumo_senders) <= summary["sumo_equipped"]


def test_the_same_seed_gives_identical_metrics_among_sumo_s_traffic_in_a_process_per_service(scenario, summary):
    again = coopdrive("run", str(scenario), "--seed", "1", "--json", "--processes", "service")
    assert again.returncode == 0, again.stdout[-2000:] + again.stderr[-2000:]
    assert {k: v for k, v in json.loads(again.stdout).items() if k not in WALL_CLOCK_KEYS} == \
        {k: v for k, v in summary.items() if k not in WALL_CLOCK_KEYS}


def test_coopdrive_run_with_a_missing_sumo_configuration_says_so_in_one_line_and_starts_nothing(scenario):
    bad = scenario.parent / "no-config.yaml"
    bad.write_text(among_traffic(follow_scenario("road.net.xml"), "{config: nowhere.sumocfg}"))
    result = coopdrive("run", str(bad))
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr == (f"coopdrive: {bad}: sumo_traffic: {scenario.parent / 'nowhere.sumocfg'}: "
                             "no such SUMO configuration file\n")
