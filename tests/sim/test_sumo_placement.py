"""Vehicles placed as SUMO places them (edge, lane, pos_m) on a SUMO network: they stand on the ground where SUMO's
own position on its lane is, through the network's projection; a reference that is not on the network is one line
naming the vehicle's key, before anything starts."""

import math
from pathlib import Path

import pytest
import sumolib

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import ScenarioError, parse_scenario

MOTORWAY = Path(__file__).resolve().parents[2] / "scenarios" / "sumo" / "motorway.net.xml"
# Metres on the ground per degree of latitude, near enough for centimetre checks over a few metres.
M_PER_DEG_LAT = 111_200.0


def scenario(vehicle: dict, map_text: str = str(MOTORWAY)) -> dict:
    return {"name": "placed", "map": map_text, "duration_s": 10,
            "vehicles": [{"vehicle_id": "ego", "station_id": 1, "lane": 0, "speed_mps": 20, **vehicle}]}


def placed(vehicle: dict):
    return parse_scenario(scenario(vehicle), "s.yaml")


def refusal(vehicle: dict, map_text: str = str(MOTORWAY)) -> str:
    with pytest.raises(ScenarioError) as refused:
        parse_scenario(scenario(vehicle, map_text), "s.yaml")
    assert "\n" not in str(refused.value)
    return str(refused.value)


@pytest.mark.parametrize("edge, lane, pos_m", [("motorway", 0, 163.6), ("motorway", 2, 2900.0), ("ramp", 0, 10.0)])
def test_a_vehicle_placed_by_edge_and_position_stands_where_sumo_s_position_is_on_the_ground(edge, lane, pos_m):
    config = placed({"edge": edge, "lane": lane, "pos_m": pos_m})
    road_map = RoadMap.load(config.map)
    model = build_scenario(config, road_map).models["ego"]
    ours = road_map.to_geodetic(model.state.x_m, model.state.y_m)
    net = sumolib.net.readNet(str(MOTORWAY))
    sumo_lane = net.getLane(f"{edge}_{lane}")
    lon_deg, lat_deg = net.convertXY2LonLat(*sumolib.geomhelper.positionAtShapeOffset(sumo_lane.getShape(), pos_m))
    north_m = (ours[0] - lat_deg) * M_PER_DEG_LAT
    east_m = (ours[1] - lon_deg) * M_PER_DEG_LAT * math.cos(math.radians(lat_deg))
    assert math.hypot(north_m, east_m) < 0.05
    assert config.vehicles[0].road == edge


def test_a_position_far_along_the_edge_is_a_station_on_the_ground_apart_from_sumo_s_projected_metres():
    # UTM's scale 2 degrees off the zone's meridian: SUMO's 2900 m along the motorway are 2900.6 m on the ground.
    assert placed({"edge": "motorway", "pos_m": 2900.0}).vehicles[0].station_m == pytest.approx(2900.56, abs=0.05)


@pytest.mark.parametrize("vehicle, problem", [
    ({"edge": "nowhere", "pos_m": 10}, "vehicles.0: edge 'nowhere': motorway.net.xml has no such edge"),
    ({"edge": "ramp", "lane": 1, "pos_m": 10}, "vehicles.0: edge 'ramp' has no lane 1 (it has 1 lanes a car may use)"),
    ({"edge": "ramp", "pos_m": 400}, "vehicles.0: pos_m 400 is off edge 'ramp' (its lane 0 is 335.76 m long)"),
    ({"edge": "ramp", "pos_m": -1}, "vehicles.0: pos_m -1 is off edge 'ramp' (its lane 0 is 335.76 m long)"),
    ({"pos_m": 10}, "vehicles.0.pos_m: a position on a SUMO edge needs the edge (edge: ID)"),
    ({"edge": "ramp"}, "vehicles.0.pos_m: a vehicle placed on a SUMO edge needs its position on it (pos_m)"),
    ({"edge": "ramp", "pos_m": 10, "station_m": 10},
     "vehicles.0.station_m: give either station_m or pos_m on the edge, not both"),
    ({"edge": "ramp", "road": "motorway", "pos_m": 10},
     "vehicles.0.edge: give either road or edge, not both (road 'motorway', edge 'ramp')"),
    ({}, "vehicles.0.station_m: Field required"),
], ids=["unknown-edge", "unknown-lane", "past-the-end", "before-the-start", "no-edge", "no-position", "both-stations",
        "both-roads", "no-station"])
def test_a_placement_that_is_not_on_the_network_is_one_line_naming_the_vehicle_and_the_problem(vehicle, problem):
    assert refusal(vehicle) == f"s.yaml: {problem}"


def test_placing_by_sumo_edge_on_a_map_that_is_not_a_sumo_network_is_one_line():
    assert refusal({"edge": "motorway", "pos_m": 10}, map_text="a270") == (
        "s.yaml: vehicles.0.edge: placing by SUMO edge needs a SUMO network as the map, not 'a270'")
