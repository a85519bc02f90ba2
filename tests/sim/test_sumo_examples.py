"""The SUMO examples shipped in scenarios/sumo/ are what SUMO's own tools make of tools/make_sumo_examples.py: the
script run here writes the same files. The motorway is a 3-lane motorway with an on-ramp, laid in Sweden by its UTM
projection; the grid a small urban grid with traffic lights."""

import subprocess
import sys
from pathlib import Path

import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.sumo_routes import network_edges, routed_edges

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = ROOT / "scenarios" / "sumo"
FILES = ("motorway.net.xml", "motorway.rou.xml", "grid.net.xml", "grid.rou.xml")


@pytest.fixture(scope="module")
def remade(tmp_path_factory):
    out = tmp_path_factory.mktemp("sumo_examples")
    result = subprocess.run([sys.executable, str(ROOT / "tools" / "make_sumo_examples.py"), "--out", str(out)],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    return out


@pytest.mark.parametrize("name", FILES)
def test_the_script_remakes_the_shipped_sumo_example_as_it_is(remade, name):
    assert (remade / name).read_text(encoding="utf-8") == (SHIPPED / name).read_text(encoding="utf-8")


def test_the_motorway_has_three_lanes_and_an_on_ramp_onto_its_right_lane_laid_in_sweden():
    road_map = RoadMap.load(SHIPPED / "motorway.net.xml")
    assert [lane.lane_id for lane in road_map.lanes_of_road("motorway")] == ["motorway_0", "motorway_1", "motorway_2"]
    assert len(road_map.lanes_of_road("approach")) == 3
    assert road_map.successors["ramp_0"] == ("motorway_0",)
    assert road_map.lane("motorway_0").length_m > 3000.0
    lat_deg, lon_deg, _ = road_map.origin
    assert lat_deg == pytest.approx(57.78, abs=0.01) and lon_deg == pytest.approx(12.79, abs=0.03)


@pytest.mark.parametrize("network, routes", [("motorway.net.xml", "motorway.rou.xml"), ("grid.net.xml", "grid.rou.xml")])
def test_every_edge_the_example_s_flows_name_is_an_edge_of_its_network(network, routes):
    assert routed_edges(SHIPPED / routes) <= network_edges(str(SHIPPED / network))


def test_the_grid_is_four_by_four_junctions_with_two_lanes_each_way_and_traffic_lights_at_all_but_its_corners():
    road_map = RoadMap.load(SHIPPED / "grid.net.xml")
    assert len({lane.road_id for lane in road_map.lanes}) == 48
    assert {len(road_map.lanes_of_road(road)) for road in {lane.road_id for lane in road_map.lanes}} == {2}
    assert (SHIPPED / "grid.net.xml").read_text(encoding="utf-8").count('<tlLogic ') == 12
