"""`coopdrive run signals`, its first 34 s with one stack verifying every packet: the roadside units' signed MAPEMs and
SPATEMs reach the stack's v2x/mapem and v2x/spatem topics, decoded to the crossroads' lanes and signal states; a
scripted car waits at its red stop line until its green; the stack, by GLOSA, reaches the first crossroads on its
green without stopping."""

import json
import subprocess
import sys

import pytest

from coopdrive.recording.reader import read_messages
from coopdrive.services.sim.signal_metrics import crossings
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.visual.signal_lanes import STATE_COLORS
from tests.visual.foxglove_mcap import foxglove_channels

pytestmark = pytest.mark.whole_run

# Through the first crossroads: its main road turns green at 30 s, when the stack, 310 m from its stop line at
# 13.9 m/s, would long have been there.
DURATION_S = 34
MAIN_GREEN_S = 30.0
RSU_A, RSU_B = 6100, 6200
# The first crossroads' side road turns green at 10 s (its plan: main road green from 30 s in a 55 s cycle).
SIDE_GREEN_S = 10.0


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    recording = tmp_path_factory.mktemp("signals") / "run.mcap"
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "run", "signals", "--stacks", "1", "--duration",
                             str(DURATION_S), "--security", "verify_required", "--json", "--record", str(recording)],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    messages = {}
    for item in read_messages(recording):
        if item.topic.endswith(("car1/v2x/mapem", "car1/v2x/spatem", "world/ground_truth")):
            messages.setdefault(item.topic.rsplit("/", 1)[-1], []).append(item.message)
    return json.loads(result.stdout), messages, recording


def test_the_run_passes_and_no_scripted_car_runs_a_red_light(run):
    summary, _, _ = run
    assert summary["success"] is True and summary["collisions"] == 0
    assert summary["signal_red_light_violations_scripted"] == 0


def test_both_roadside_units_mapems_reach_the_stack_with_ingress_lanes_starting_at_their_stop_lines(run):
    _, messages, _ = run
    mapems = {m.station_id: m for m in messages["mapem"]}
    assert set(mapems) == {RSU_A, RSU_B}
    intersection = mapems[RSU_A].intersections[0]
    assert (intersection.id.id, list(intersection.signal_groups)) == (1, [1, 2, 3, 4])
    eastbound = next(lane for lane in intersection.lanes if lane.lane_id == 1)
    assert (eastbound.nodes[0].east_m, eastbound.nodes[0].north_m) == (pytest.approx(-10.0), pytest.approx(-1.75))
    assert [(c.to_lane_id, c.signal_group) for c in eastbound.connections] == [(2, 1)]


def test_the_stacks_spatems_say_what_the_controller_shows(run):
    _, messages, _ = run
    spatems = [m for m in messages["spatem"] if m.station_id == RSU_A]
    assert len(spatems) > 10 * DURATION_S / 2
    # 10:00:00 UTC at the start: seconds of the hour are the run's. The main road is green until 5 s, then amber.
    first = spatems[0].intersections[0].signal_groups[0]
    assert (first.signal_group, first.events[0].state, first.events[0].min_end_time_s) == \
        (1, pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED, pytest.approx(5.0))
    # The last SPATEM heard and the last truth are within a tenth of a second, 2 s from any change (side green 10-25 s).
    truth = {(s.intersection_id, s.signal_group): s.state for s in messages["ground_truth"][-1].signals}
    last = {g.signal_group: g.events[0].state for g in spatems[-1].intersections[0].signal_groups}
    assert last == {group: truth[(1, group)] for group in (1, 2, 3, 4)}


def test_the_stack_arrives_at_the_first_crossroads_on_green_without_stopping_and_never_enters_on_red(run):
    summary, messages, _ = run
    assert summary["signal_red_light_violations"] == 0
    frames = [(m.header.sample_time_s, m.vehicles, m.signals) for m in messages["ground_truth"]]
    (crossing,) = [c for c in crossings(frames) if c.vehicle_id == "car1"]
    assert crossing.time_s >= MAIN_GREEN_S and not crossing.red and crossing.stops == 0
    # GLOSA: slowed to arrive on green, never stood.
    assert min(v.speed_mps for _, vehicles, _ in frames for v in vehicles if v.vehicle_id == "car1") > 1.0


def test_the_scripted_car_on_the_side_road_stops_at_its_red_and_crosses_on_green(run):
    _, messages, _ = run
    frames = [(m.header.sample_time_s, m.vehicles, m.signals) for m in messages["ground_truth"]]
    speeds = [v.speed_mps for time_s, vehicles, _ in frames for v in vehicles
              if v.vehicle_id == "north_car" and time_s < SIDE_GREEN_S]
    assert min(speeds) < 0.1
    (crossing,) = [c for c in crossings(frames) if c.vehicle_id == "north_car"]
    assert crossing.time_s >= SIDE_GREEN_S and not crossing.red


def test_foxglove_draws_both_crossroads_lanes_with_each_movement_in_the_colour_of_the_last_spat(run):
    _, messages, recording = run
    drawn = foxglove_channels(recording)["foxglove/car1/signals"]
    assert len(drawn) >= len(messages["spatem"])
    movements = {f["properties"]["name"]: f["properties"]["style"]["color"]
                 for f in json.loads(drawn[-1].geojson)["features"] if "signal group" in f["properties"]["name"]}
    assert {name.split(" lane")[0] for name in movements} == {"intersection 0/1", "intersection 0/2"}
    last = {g.signal_group: g.events[0].state
            for g in [m for m in messages["spatem"] if m.station_id == RSU_A][-1].intersections[0].signal_groups}
    for name, colour in movements.items():
        if name.startswith("intersection 0/1"):
            group = int(name.split("signal group ")[1].split(":")[0])
            assert colour == STATE_COLORS[last[group]], name
