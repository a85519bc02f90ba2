"""The guide docs/how-to/sumo-network.md as written: its netgenerate command builds the network its scenario file
names, and that file loads and places its vehicles on the network's lanes; with its flow file and its sumo_traffic
lines, the file names SUMO traffic that SUMO drives among them (its `coopdrive run` lines are parsed with the other
documented commands; tests/sim/test_sumo_runs.py and test_sumo_traffic_runs.py run such files end to end)."""

import re
import shlex
import subprocess
from pathlib import Path

import yaml

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.scenario_config import load_scenario
from tests.sumo_networks import NETGENERATE

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "how-to" / "sumo-network.md"
BLOCK = re.compile(r"^```(sh|yaml|xml)\n(.*?)^```", re.MULTILINE | re.DOTALL)
# The names the guide saves its scenario files and its flow under.
SCENARIO_FILE = "sumo-follow.yaml"
TRAFFIC_FILE = "sumo-traffic.yaml"
FLOW_FILE = "flow.rou.xml"


def guide_blocks(kind: str) -> list[str]:
    return [text for found, text in BLOCK.findall(GUIDE.read_text(encoding="utf-8")) if found == kind]


def test_the_guide_s_network_and_scenario_file_load_and_place_its_vehicles_on_the_network_s_lanes(tmp_path):
    commands = [shlex.split(line) for block in guide_blocks("sh") for line in block.splitlines() if line.strip()]
    assert [command[0] for command in commands] == ["netgenerate", "coopdrive", "coopdrive"]
    built = subprocess.run([str(NETGENERATE), *commands[0][1:]], capture_output=True, text=True, timeout=120,
                           cwd=tmp_path)
    assert built.returncode == 0, built.stderr
    scenario_text, _ = guide_blocks("yaml")
    assert f"`{SCENARIO_FILE}`" in GUIDE.read_text(encoding="utf-8")
    (tmp_path / SCENARIO_FILE).write_text(scenario_text, encoding="utf-8")
    config = load_scenario(tmp_path / SCENARIO_FILE)
    assert config.map == str(tmp_path.resolve() / yaml.safe_load(scenario_text)["map"])
    objects = build_scenario(config, RoadMap.load(config.map))
    assert [lane.lane_id for lane in objects.lanes["ego"]] == ["A0B0_0", "A0B0_1"]
    assert [lane.lane_id for lane in objects.lanes["leader"]] == ["A0B0_0", "A0B0_1"]


def test_the_guide_s_flow_and_sumo_traffic_lines_make_sumo_drive_its_cars_among_the_scenario_s(tmp_path):
    from coopdrive.services.sim.scenario_sim import ScenarioSim

    netgenerate_line = shlex.split(guide_blocks("sh")[0])
    subprocess.run([str(NETGENERATE), *netgenerate_line[1:]], check=True, capture_output=True, cwd=tmp_path)
    scenario_text, traffic_text = guide_blocks("yaml")
    [flow_text] = guide_blocks("xml")
    for name in (TRAFFIC_FILE, FLOW_FILE):
        assert f"`{name}`" in GUIDE.read_text(encoding="utf-8")
    (tmp_path / FLOW_FILE).write_text(flow_text, encoding="utf-8")
    (tmp_path / TRAFFIC_FILE).write_text(scenario_text + traffic_text, encoding="utf-8")
    config = load_scenario(tmp_path / TRAFFIC_FILE)
    assert config.sumo_traffic.routes == [str(tmp_path.resolve() / FLOW_FILE)]
    sim = ScenarioSim(config, RoadMap.load(config.map), ["ego"])
    try:
        for step in range(1, 151):
            sim.step(step * config.step_s)
        assert sim.traffic_metrics()["sumo_vehicles"] >= 1
    finally:
        sim.close()
