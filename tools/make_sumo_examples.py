"""Makes the SUMO examples shipped in scenarios/sumo/ with SUMO's own tools (the eclipse-sumo package):

- motorway.net.xml: a 3-lane motorway with an on-ramp, built by netconvert from plain node and edge XML whose nodes are
  in latitude and longitude (laid near AstaZero, Sweden), projected by netconvert in their UTM zone (33), as netconvert
  projects a network it builds from OpenStreetMap. The edge `approach` (1 km, 3 lanes) and the on-ramp `ramp` (one
  lane) meet at junction `j`, where the ramp gives way; the edge `motorway` (3 km, 3 lanes) goes on from there.
  120 km/h on the motorway, 80 km/h on the ramp.
- motorway.rou.xml: dense traffic: the approach, the ramp and the motorway's two left lanes filled in the first
  seconds (98 cars), then a steady flow on the motorway and onto it from the ramp.
- grid.net.xml and grid.rou.xml: a small urban grid by netgenerate (4 x 4 junctions 150 m apart, two lanes each way
  at 50 km/h, traffic lights), with flows across it.

netconvert's and netgenerate's header comment (the date, this machine's paths) is left out, so that the files are
the same on every run: tests/sim/test_sumo_examples.py runs this script and compares.

    python tools/make_sumo_examples.py [--out scenarios/sumo]
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import pyproj
import sumo

BIN = Path(sumo.SUMO_HOME) / "bin"
OUT = Path(__file__).resolve().parents[1] / "scenarios" / "sumo"
# Near AstaZero, Sweden: the motorway's node w, from which the others are laid east and north in metres (UTM 33).
ORIGIN_LAT_LON_DEG = (57.7785, 12.7720)
UTM_33 = "+proj=utm +zone=33 +ellps=WGS84 +datum=WGS84 +units=m +no_defs"
MOTORWAY_SPEED_MPS = 33.33
RAMP_SPEED_MPS = 22.22
# The motorway's nodes, metres east and north of w: the ramp meets the motorway at j, 1 km on.
MOTORWAY_NODES_M = {"w": (0.0, 0.0), "j": (1000.0, 0.0), "e": (4000.0, 0.0), "r": (600.0, -60.0)}
# id, from, to, lanes, speed, priority (the ramp's lower priority makes it give way at j)
MOTORWAY_EDGES = (("approach", "w", "j", 3, MOTORWAY_SPEED_MPS, 3),
                  ("motorway", "j", "e", 3, MOTORWAY_SPEED_MPS, 3),
                  ("ramp", "r", "j", 1, RAMP_SPEED_MPS, 1))
# The generated-on comment netconvert and netgenerate write at a file's top.
_HEADER = re.compile(r"\n<!-- generated on .*?-->\n", re.DOTALL)

MOTORWAY_ROUTES = """<routes>
    <!-- Cars of SUMO's default model (Krauss, LC2013), each with its own speed factor about the limit. -->
    <vType id="car" vClass="passenger" length="4.5" width="1.8" speedFactor="normc(1,0.1,0.8,1.2)"/>
    <vType id="truck" vClass="truck" length="12.0" width="2.5" maxSpeed="25.0"/>
    <route id="through" edges="approach motorway"/>
    <route id="onto" edges="ramp motorway"/>
    <route id="ahead" edges="motorway"/>
    <!-- The approach and the ramp filled in the first seconds, and the motorway's two left lanes beside and ahead
         of the scenario's vehicles, which drive on its right lane. -->
    <flow id="approach_fill" type="car" route="through" begin="0.5" end="3" number="60" departLane="random"
          departPos="random_free" departSpeed="max"/>
    <flow id="ahead_1" type="car" route="ahead" begin="0.5" end="3" number="15" departLane="1"
          departPos="random_free" departSpeed="max"/>
    <flow id="ahead_2" type="car" route="ahead" begin="0.5" end="3" number="15" departLane="2"
          departPos="random_free" departSpeed="max"/>
    <flow id="ramp_fill" type="car" route="onto" begin="0.5" end="3" number="8" departPos="random_free"
          departSpeed="max"/>
    <!-- 900 cars an hour from the ramp, from the start; then (SUMO reads flows in the order they begin) a steady flow
         of 3000 cars and 300 trucks an hour on the motorway. -->
    <flow id="merging" type="car" route="onto" begin="0.5" end="3600" vehsPerHour="900" departSpeed="max"/>
    <flow id="main" type="car" route="through" begin="3" end="3600" vehsPerHour="3000" departLane="best"
          departSpeed="max"/>
    <flow id="main_trucks" type="truck" route="through" begin="3" end="3600" vehsPerHour="300" departLane="0"
          departSpeed="max"/>
</routes>
"""

GRID_ROUTES = """<routes>
    <vType id="car" vClass="passenger" length="4.5" width="1.8"/>
    <!-- Across the grid both ways, east-west and north-south; SUMO routes each from its first edge to its last. -->
    <flow id="eastbound" type="car" from="A0B0" to="C0D0" begin="0.5" end="3600" vehsPerHour="600" departSpeed="max"/>
    <flow id="westbound" type="car" from="D3C3" to="B3A3" begin="0.5" end="3600" vehsPerHour="600" departSpeed="max"/>
    <flow id="northbound" type="car" from="A0A1" to="A2A3" begin="0.5" end="3600" vehsPerHour="400" departSpeed="max"/>
    <flow id="southbound" type="car" from="D3D2" to="D1D0" begin="0.5" end="3600" vehsPerHour="400" departSpeed="max"/>
</routes>
"""


def run_tool(tool: str, *options: str) -> None:
    # PROJ's own data (proj.db) is pyproj's: SUMO's tools find it there, silently, instead of warning they cannot.
    environment = {**os.environ, "PROJ_DATA": pyproj.datadir.get_data_dir()}
    result = subprocess.run([str(BIN / tool), *options], capture_output=True, text=True, timeout=300,
                            env=environment)
    if result.returncode != 0:
        raise SystemExit(f"{tool} failed: {' '.join(result.stderr.split())}")


def without_header(path: Path) -> None:
    path.write_text(_HEADER.sub("\n", path.read_text(encoding="utf-8"), count=1), encoding="utf-8")


def motorway_nodes_xml() -> str:
    """The nodes in longitude and latitude (netconvert's plain XML with --proj.utm), from metres east and north of w
    in UTM 33."""
    projection = pyproj.Proj(UTM_33)
    w_east_m, w_north_m = projection(ORIGIN_LAT_LON_DEG[1], ORIGIN_LAT_LON_DEG[0])
    lines = []
    for node_id, (east_m, north_m) in MOTORWAY_NODES_M.items():
        lon_deg, lat_deg = projection(w_east_m + east_m, w_north_m + north_m, inverse=True)
        lines.append(f'    <node id="{node_id}" x="{lon_deg:.8f}" y="{lat_deg:.8f}" type="priority"/>')
    return "<nodes>\n" + "\n".join(lines) + "\n</nodes>\n"


def motorway_edges_xml() -> str:
    lines = [f'    <edge id="{edge}" from="{start}" to="{end}" numLanes="{lanes}" speed="{speed}" priority="{priority}"/>'
             for edge, start, end, lanes, speed, priority in MOTORWAY_EDGES]
    return "<edges>\n" + "\n".join(lines) + "\n</edges>\n"


def make_motorway(out: Path, work: Path) -> None:
    (work / "motorway.nod.xml").write_text(motorway_nodes_xml(), encoding="utf-8")
    (work / "motorway.edg.xml").write_text(motorway_edges_xml(), encoding="utf-8")
    network = out / "motorway.net.xml"
    run_tool("netconvert", "--node-files", str(work / "motorway.nod.xml"), "--edge-files",
             str(work / "motorway.edg.xml"), "--proj.utm", "--no-turnarounds", "--output-file", str(network))
    without_header(network)
    (out / "motorway.rou.xml").write_text(MOTORWAY_ROUTES, encoding="utf-8")


def make_grid(out: Path) -> None:
    network = out / "grid.net.xml"
    run_tool("netgenerate", "--grid", "--grid.number", "4", "--grid.length", "150", "--default.lanenumber", "2",
             "--default.speed", "13.89", "--tls.guess", "--no-turnarounds", "--output-file", str(network))
    without_header(network)
    (out / "grid.rou.xml").write_text(GRID_ROUTES, encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=OUT, help="the folder to write the examples to")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        make_motorway(args.out, Path(work))
    make_grid(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
