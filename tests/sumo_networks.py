"""SUMO networks made at test time by SUMO's own netgenerate (the eclipse-sumo package, a test dependency), and
geo-referenced as netconvert references a network it builds from OpenStreetMap: a UTM projection in the location
element, with the offset that puts the network's (0, 0) on a given latitude and longitude."""

from __future__ import annotations

import math
import re
import subprocess
from pathlib import Path

import pyproj
import sumo

NETGENERATE = Path(sumo.SUMO_HOME) / "bin" / "netgenerate"

# The straight road: one 2 km edge each way between two nodes, two lanes each.
STRAIGHT_LENGTH_M = 2000.0
STRAIGHT_LANES = 2
STRAIGHT_LANE_WIDTH_M = 3.5
STRAIGHT_SPEED_MPS = 27.78
# The grid: 3 x 3 junctions 200 m apart, one lane each way with a sidewalk on its right (SUMO's lane 0).
GRID_NODES = 3
GRID_SPACING_M = 200.0
GRID_LANE_WIDTH_M = 3.0
GRID_SPEED_MPS = 13.89
# AstaZero, Sweden (UTM zone 33): far from the default origin, so that a network laid there is seen to be.
ASTAZERO_LAT_LON_DEG = (57.7785, 12.7720)
_LOCATION = re.compile(r'netOffset="[^"]*"(.*?)projParameter="[^"]*"')


def netgenerate(path: Path, *options: str) -> Path:
    """Runs netgenerate with the options, writing the network to path."""
    result = subprocess.run([str(NETGENERATE), *options, "--output-file", str(path)], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    return path


def straight_road(path: Path) -> Path:
    return netgenerate(path, "--grid", "--grid.x-number", "2", "--grid.y-number", "1",
                       "--grid.x-length", str(STRAIGHT_LENGTH_M), "--default.lanenumber", str(STRAIGHT_LANES),
                       "--default.lanewidth", str(STRAIGHT_LANE_WIDTH_M), "--default.speed", str(STRAIGHT_SPEED_MPS))


def grid_with_sidewalks(path: Path) -> Path:
    return netgenerate(path, "--grid", "--grid.number", str(GRID_NODES), "--grid.length", str(GRID_SPACING_M),
                       "--default.lanenumber", "1", "--default.lanewidth", str(GRID_LANE_WIDTH_M),
                       "--default.speed", str(GRID_SPEED_MPS), "--sidewalks.guess")


def footpaths_only(path: Path) -> Path:
    """A network whose every lane is for pedestrians."""
    return netgenerate(path, "--grid", "--grid.number", "2", "--grid.length", "100", "--default.allow", "pedestrian")


def geo_referenced(path: Path, lat_deg: float, lon_deg: float) -> Path:
    """The network with its (0, 0) at lat_deg, lon_deg in that place's UTM zone."""
    zone = int(math.floor((lon_deg + 180.0) / 6.0)) + 1
    projection = f"+proj=utm +zone={zone} +ellps=WGS84 +datum=WGS84 +units=m +no_defs"
    east_m, north_m = pyproj.Proj(projection)(lon_deg, lat_deg)
    text, count = _LOCATION.subn(
        lambda found: f'netOffset="{-east_m:.2f},{-north_m:.2f}"{found.group(1)}projParameter="{projection}"',
        path.read_text(encoding="utf-8"), count=1)
    assert count == 1, f"{path} has no location element"
    path.write_text(text, encoding="utf-8")
    return path


def follow_scenario(map_text: str, duration_s: float = 30.0) -> str:
    """The follow scenario's leader and stack on the straight road's eastbound edge, its map named as given."""
    return f"""
name: sumo-follow
description: A scripted leader changes speed on a SUMO network; the ego stack follows.
map: {map_text}
seed: 1
duration_s: {duration_s}
vehicles:
  - vehicle_id: leader
    station_id: 1001
    role: scripted
    road: A0B0
    lane: 0
    station_m: 45
    speed_mps: 15
    speed_profile:
      kind: piecewise
      points:
        - {{time_s: 0, speed_mps: 15}}
        - {{time_s: 4, speed_mps: 15}}
        - {{time_s: 10, speed_mps: 22}}
        - {{time_s: 16, speed_mps: 22}}
        - {{time_s: 20, speed_mps: 10}}
  - {{vehicle_id: ego, station_id: 1002, road: A0B0, lane: 0, station_m: 0, speed_mps: 15}}
judging:
  platoon: [leader, ego]
  standstill_m: 6.0
  headway_s: 1.5
"""


def with_roads(folder: Path) -> Path:
    """The folder, with roads/ beside where its scenario files go: the straight road, a network of footpaths only,
    and a routes file."""
    (folder / "roads").mkdir()
    straight_road(folder / "roads" / "straight.net.xml")
    footpaths_only(folder / "roads" / "footpaths.net.xml")
    (folder / "roads" / "routes.rou.xml").write_text('<routes><vehicle id="a" depart="0"/></routes>\n')
    return folder


def scenario_file(folder: Path, map_text: str, name: str) -> Path:
    """The follow scenario on the straight road's map named as given, written to folder/name."""
    path = folder / name
    path.write_text(follow_scenario(map_text))
    return path


# SUMO's traffic of the tests: cars of a size of their own (not SUMO's default 5 m x 1.8 m), so that the truth is
# seen to take it from their type.
SUMO_CAR_LENGTH_M = 4.2
SUMO_CAR_WIDTH_M = 1.9


def flow_routes(path: Path, number: int = 20, edges: str = "A0B0", lane: str = "random", begin_s: float = 0.0,
                end_s: float = 20.0, speed: str = "max") -> Path:
    """A routes file with one flow of `number` cars over `edges`, departing evenly from begin_s to end_s."""
    path.write_text(f"""<routes>
    <vType id="car" length="{SUMO_CAR_LENGTH_M}" width="{SUMO_CAR_WIDTH_M}"/>
    <route id="through" edges="{edges}"/>
    <flow id="traffic" type="car" route="through" begin="{begin_s}" end="{end_s}" number="{number}"
          departLane="{lane}" departSpeed="{speed}"/>
</routes>
""", encoding="utf-8")
    return path


def sumo_config(path: Path, routes_name: str) -> Path:
    """A SUMO configuration (.sumocfg) that lists the routes file beside it."""
    path.write_text(f"""<configuration>
    <input>
        <route-files value="{routes_name}"/>
    </input>
</configuration>
""", encoding="utf-8")
    return path


def among_traffic(scenario_text: str, traffic_yaml: str) -> str:
    """The scenario with SUMO traffic (the YAML of its sumo_traffic mapping, e.g. "{routes: [flow.rou.xml]}")."""
    return scenario_text + f"sumo_traffic: {traffic_yaml}\n"
