"""The guide docs/how-to/sumo-network.md as written: its netgenerate command builds the network its scenario file
names, and that file loads and places its vehicles on the network's lanes (its `coopdrive run` line is parsed with the
other documented commands; tests/sim/test_sumo_follow_run.py runs such a file end to end)."""

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
BLOCK = re.compile(r"^```(sh|yaml)\n(.*?)^```", re.MULTILINE | re.DOTALL)
# The name the guide saves its scenario file under.
SCENARIO_FILE = "sumo-follow.yaml"


def guide_blocks(kind: str) -> list[str]:
    return [text for found, text in BLOCK.findall(GUIDE.read_text(encoding="utf-8")) if found == kind]


def test_the_guide_s_network_and_scenario_file_load_and_place_its_vehicles_on_the_network_s_lanes(tmp_path):
    commands = [shlex.split(line) for block in guide_blocks("sh") for line in block.splitlines() if line.strip()]
    assert [command[0] for command in commands] == ["netgenerate", "coopdrive"]
    built = subprocess.run([str(NETGENERATE), *commands[0][1:]], capture_output=True, text=True, timeout=120,
                           cwd=tmp_path)
    assert built.returncode == 0, built.stderr
    [scenario_text] = guide_blocks("yaml")
    assert f"`{SCENARIO_FILE}`" in GUIDE.read_text(encoding="utf-8")
    (tmp_path / SCENARIO_FILE).write_text(scenario_text, encoding="utf-8")
    config = load_scenario(tmp_path / SCENARIO_FILE)
    assert config.map == str(tmp_path.resolve() / yaml.safe_load(scenario_text)["map"])
    objects = build_scenario(config, RoadMap.load(config.map))
    assert [lane.lane_id for lane in objects.lanes["ego"]] == ["A0B0_0", "A0B0_1"]
    assert [lane.lane_id for lane in objects.lanes["leader"]] == ["A0B0_0", "A0B0_1"]
