"""SUMO's traffic among our vehicles, stepped in this process (libsumo) by the simulator's world (ScenarioSim) without
stacks: a network and a flow of cars built at test time. SUMO's cars stand in our ground truth where libsumo puts them
(checked through SUMO's own projection, on a network laid in Sweden) with their type's size; ours stand in SUMO where
they are in ours; SUMO's drivers brake behind our slow car rather than run into it; a seed gives the same traffic
twice. A SUMO configuration or routes file that cannot be run: one line, before anything starts."""

import math

import libsumo
import numpy as np
import pytest
import yaml

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim import metrics
from coopdrive.services.sim.scenario_config import ScenarioError, load_scenario, parse_scenario
from coopdrive.services.sim.scenario_sim import ScenarioSim
from coopdrive.services.sim.sumo_traffic import front_bumper_xy
from coopdrive.services.sim.truth_series import TruthSeries
from tests.sumo_networks import (ASTAZERO_LAT_LON_DEG, SUMO_CAR_LENGTH_M, SUMO_CAR_WIDTH_M, among_traffic,
                                 flow_routes, follow_scenario, geo_referenced, netgenerate, straight_road,
                                 sumo_config)

STEP_S = 0.02
# Metres on the ground per degree of latitude, near enough for half-metre checks at AstaZero.
M_PER_DEG_LAT = 111_200.0


def world(folder, scenario_text: str, stacks=("ego",)) -> ScenarioSim:
    path = folder / "scenario.yaml"
    path.write_text(scenario_text)
    config = load_scenario(path)
    return ScenarioSim(config, RoadMap.load(config.map), list(stacks))


def run_for(sim: ScenarioSim, duration_s: float) -> list[tuple[float, list]]:
    """The world's truths every 0.1 s over the next duration_s."""
    frames = []
    first = round(sim.time_s / STEP_S) + 1
    for step in range(first, first + round(duration_s / STEP_S)):
        sim.step(step * STEP_S)
        if step % 5 == 0:
            frames.append((step * STEP_S, sim.truths()))
    return frames


@pytest.fixture
def astazero(tmp_path):
    """The follow scenario among 20 SUMO cars on the straight road laid at AstaZero; SUMO closed at the end."""
    network = geo_referenced(straight_road(tmp_path / "astazero.net.xml"), *ASTAZERO_LAT_LON_DEG)
    flow_routes(tmp_path / "flow.rou.xml", begin_s=1.0, end_s=6.0)
    sim = world(tmp_path, among_traffic(follow_scenario(network.name), "{routes: [flow.rou.xml]}"))
    yield sim
    sim.close()


def ground_distance_m(lat_lon_a: tuple[float, float], lat_lon_b: tuple[float, float]) -> float:
    north_m = (lat_lon_a[0] - lat_lon_b[0]) * M_PER_DEG_LAT
    east_m = (lat_lon_a[1] - lat_lon_b[1]) * M_PER_DEG_LAT * math.cos(math.radians(lat_lon_a[0]))
    return math.hypot(north_m, east_m)


def test_sumo_s_cars_stand_in_our_ground_truth_where_libsumo_puts_them_within_half_a_metre(astazero):
    road_map = RoadMap.load(astazero.config.map)
    checked = set()
    for _ in range(10):
        run_for(astazero, 1.0)
        for truth in astazero.truths()[2:]:
            ours = road_map.to_geodetic(*front_bumper_xy(truth.x_m, truth.y_m, truth.heading_rad, truth.length_m))
            lon_deg, lat_deg = libsumo.simulation.convertGeo(*libsumo.vehicle.getPosition(truth.vehicle_id))
            assert ground_distance_m(ours[:2], (lat_deg, lon_deg)) < 0.5
            assert (truth.length_m, truth.width_m) == pytest.approx((SUMO_CAR_LENGTH_M, SUMO_CAR_WIDTH_M))
            assert truth.speed_mps == pytest.approx(libsumo.vehicle.getSpeed(truth.vehicle_id))
            checked.add(truth.vehicle_id)
    assert len(checked) >= 10


def test_our_vehicles_stand_in_sumo_where_they_are_in_our_world(astazero):
    run_for(astazero, 3.0)
    road_map = RoadMap.load(astazero.config.map)
    for truth in astazero.truths()[:2]:
        ours = road_map.to_geodetic(*front_bumper_xy(truth.x_m, truth.y_m, truth.heading_rad, truth.length_m))
        lon_deg, lat_deg = libsumo.simulation.convertGeo(*libsumo.vehicle.getPosition(truth.vehicle_id))
        assert ground_distance_m(ours[:2], (lat_deg, lon_deg)) < 0.05
        assert libsumo.vehicle.getLength(truth.vehicle_id) == pytest.approx(truth.length_m)


def test_sumo_s_drivers_brake_behind_our_slow_car_on_a_one_lane_road_rather_than_run_into_it(tmp_path):
    netgenerate(tmp_path / "lane.net.xml", "--grid", "--grid.x-number", "2", "--grid.y-number", "1",
                "--grid.x-length", "1000", "--default.lanenumber", "1", "--default.speed", "27.78")
    flow_routes(tmp_path / "flow.rou.xml", number=5, lane="0", begin_s=0.5, end_s=3.0)
    scenario = yaml.safe_load(follow_scenario("lane.net.xml"))
    scenario["vehicles"] = [{"vehicle_id": "ego", "station_id": 1002, "road": "A0B0", "lane": 0, "station_m": 60,
                             "speed_mps": 8}]
    scenario["judging"] = {}
    sim = world(tmp_path, among_traffic(yaml.safe_dump(scenario), "{routes: [flow.rou.xml]}"))
    try:
        frames = run_for(sim, 15.0)
        figures = sim.traffic_metrics()
    finally:
        sim.close()
    behind = [truth for truth in frames[-1][1][1:] if truth.station_m < frames[-1][1][0].station_m]
    # Free, they would drive at the road's 27.8 m/s; behind ours they are down to about its 8 m/s.
    assert len(behind) == 5 and max(truth.speed_mps for truth in behind) < 10.0
    assert metrics.collisions(TruthSeries.from_frames(frames), ours={"ego"}) == 0
    assert figures["sumo_collisions"] == 0 and figures["sumo_vehicles"] == 5


def final_positions(folder, seed: int) -> np.ndarray:
    sim = world(folder, among_traffic(follow_scenario("road.net.xml"), "{routes: [flow.rou.xml]}").replace(
        "seed: 1", f"seed: {seed}"))
    try:
        frames = run_for(sim, 6.0)
    finally:
        sim.close()
    return np.array([(t.x_m, t.y_m, t.speed_mps) for t in frames[-1][1]])


def test_one_seed_gives_the_same_sumo_traffic_twice_and_another_seed_other_traffic(tmp_path):
    straight_road(tmp_path / "road.net.xml")
    flow_routes(tmp_path / "flow.rou.xml", begin_s=1.0, end_s=5.0)
    first, again, other = (final_positions(tmp_path, seed) for seed in (1, 1, 2))
    assert len(first) > 5 and np.array_equal(first, again)
    assert len(other) != len(first) or not np.array_equal(first, other)


def test_a_sumo_configuration_s_routes_files_are_driven(tmp_path):
    straight_road(tmp_path / "road.net.xml")
    flow_routes(tmp_path / "flow.rou.xml", number=4, begin_s=1.0, end_s=3.0)
    sumo_config(tmp_path / "traffic.sumocfg", "flow.rou.xml")
    sim = world(tmp_path, among_traffic(follow_scenario("road.net.xml"), "{config: traffic.sumocfg}"))
    try:
        run_for(sim, 5.0)
        assert sim.traffic_metrics()["sumo_vehicles"] == 4
    finally:
        sim.close()


@pytest.fixture
def road(tmp_path):
    straight_road(tmp_path / "road.net.xml")
    return tmp_path


def refusal(folder, traffic_yaml: str, map_text: str = "road.net.xml") -> str:
    with pytest.raises(ScenarioError) as refused:
        parse_scenario(yaml.safe_load(among_traffic(follow_scenario(map_text), traffic_yaml)), "s.yaml", folder)
    assert "\n" not in str(refused.value)
    return str(refused.value)


def test_a_missing_sumo_configuration_is_one_line_naming_it(road):
    assert refusal(road, "{config: nowhere.sumocfg}") == (
        f"s.yaml: sumo_traffic: {road / 'nowhere.sumocfg'}: no such SUMO configuration file")


def test_a_missing_routes_file_of_a_sumo_configuration_is_one_line_naming_it(road):
    sumo_config(road / "traffic.sumocfg", "gone.rou.xml")
    assert refusal(road, "{config: traffic.sumocfg}") == (
        f"s.yaml: sumo_traffic: {road / 'gone.rou.xml'}: no such SUMO routes file")


def test_a_route_through_edges_the_network_does_not_have_is_one_line_naming_them(road):
    flow_routes(road / "flow.rou.xml", edges="A0B0 B0C0 Z9")
    assert refusal(road, "{routes: [flow.rou.xml]}") == (
        f"s.yaml: sumo_traffic: {road / 'flow.rou.xml'}: a route goes through edges that road.net.xml does not have: "
        "B0C0, Z9")


def test_sumo_traffic_on_a_map_that_is_not_a_sumo_network_is_one_line(road):
    flow_routes(road / "flow.rou.xml")
    assert refusal(road, "{routes: [flow.rou.xml]}", map_text="a270") == (
        "s.yaml: sumo_traffic: SUMO traffic needs a SUMO network as the map, not 'a270'")


def test_sumo_traffic_naming_both_a_configuration_and_routes_is_one_line(road):
    assert "not both or none" in refusal(road, "{config: a.sumocfg, routes: [b.rou.xml]}")


def test_an_equipped_share_of_sumo_s_cars_send_cams_of_where_they_are_at_their_rate(tmp_path):
    straight_road(tmp_path / "road.net.xml")
    flow_routes(tmp_path / "flow.rou.xml", number=10, begin_s=0.5, end_s=3.0)
    sim = world(tmp_path, among_traffic(follow_scenario("road.net.xml"),
                                        "{routes: [flow.rou.xml], equipped_share: 0.5, cam_rate_hz: 10}"))
    try:
        run_for(sim, 5.0)
        sent = {}
        for step in range(1, 51):
            sim.step(5.0 + step * STEP_S)
            truths = {t.vehicle_id: t for t in sim.truths()}
            for intent in sim.intents(sim.time_s):
                if intent.station_id >= 900_000:
                    sent.setdefault(intent.sender_id, []).append(intent)
                    assert intent.fields["x_m"] == truths[intent.sender_id].x_m
        figures = sim.traffic_metrics()
    finally:
        sim.close()
    assert figures["sumo_vehicles"] == 10 and 1 <= figures["sumo_equipped"] <= 9
    assert len(sent) == figures["sumo_equipped"]
    # At 10 Hz, after the first (the gate's missed periods are skipped, not caught up).
    for cams in sent.values():
        assert np.diff([cam.time_s for cam in cams[1:]]) == pytest.approx([0.1] * (len(cams) - 2))
