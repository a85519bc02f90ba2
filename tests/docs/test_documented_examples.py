"""The YAML examples of the how-to guides are what the code accepts: the scenario file, its faults and its traffic
lights, the vehicle CAN adapter (against the RAV4's DBC it names) and the gateway's secure config."""

import re
from pathlib import Path

import yaml

from coopdrive.can.adapter import load_adapter
from coopdrive.services.gateway.config import GatewayConfig
from coopdrive.services.sim.scenario_config import parse_scenario

DOCS = Path(__file__).resolve().parents[2] / "docs"
YAML_BLOCK = re.compile(r"^```yaml\n(.*?)^```", re.MULTILINE | re.DOTALL)
RAV4_FOLDER = DOCS.parent / "deploy" / "vehicles"


def yaml_blocks(page: str) -> list:
    return [yaml.safe_load(block) for block in YAML_BLOCK.findall((DOCS / page).read_text(encoding="utf-8"))]


def test_the_scenario_guide_s_file_and_its_faults_are_a_valid_scenario():
    scenario, faults, signals = yaml_blocks("how-to/scenario-file.md")
    parsed = parse_scenario({**scenario, **faults, **signals}, "docs/how-to/scenario-file.md")
    assert parsed.name == "my-follow"
    assert [fault.type for fault in parsed.faults] == ["gnss_outage", "gnss_jump", "radar_clutter", "partner_silent"]
    plan = parsed.roadside_units[0].intersection.plan
    assert (plan.cycle_s, plan.stages[1].max_extension_s) == (55.0, 10.0)


def test_the_can_guide_s_adapter_loads_against_the_rav4_dbc(tmp_path):
    [adapter] = yaml_blocks("how-to/vehicle-can.md")
    path = tmp_path / "my_car.yaml"
    path.write_text(yaml.safe_dump({**adapter, "dbc": str(RAV4_FOLDER / adapter["dbc"])}), encoding="utf-8")
    loaded, _ = load_adapter(path)
    assert tuple(loaded.quantities["yaw_rate"].signals) == ("YAW_RATE",)


def test_the_gateway_guide_s_secure_config_is_a_valid_gateway_config():
    [config] = yaml_blocks("how-to/gateway.md")
    parsed = GatewayConfig.model_validate(config)
    assert parsed.readonly_open is False and set(parsed.tokens) == {"alice", "pit-wall"}
