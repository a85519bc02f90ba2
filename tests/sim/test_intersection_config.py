"""A signalised intersection in a scenario file: a plan and approaches that do not fit each other or the map, or a
signal fault naming no such unit, are refused with one line naming what was wrong; a unit's fault acts from its
start to its end."""

from pathlib import Path

import pytest
import yaml

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import build_scenario
from coopdrive.services.sim.participants import IntentKind
from coopdrive.services.sim.scenario_config import ScenarioError, parse_scenario
from coopdrive.services.sim.scenario_sim import ScenarioSim

SIGNALS = Path(__file__).resolve().parents[2] / "scenarios" / "signals.yaml"


def signals(change) -> dict:
    data = yaml.safe_load(SIGNALS.read_text(encoding="utf-8"))
    change(data["roadside_units"][0]["intersection"])
    return data


def test_an_approach_whose_signal_group_is_in_no_stage_is_refused_naming_the_intersection_and_the_group():
    def group_9(intersection):
        intersection["approaches"][0]["signal_group"] = 9
    with pytest.raises(ScenarioError,
                       match=r"roadside_units\.0\.intersection\.approaches: signal groups \[9\] are in no stage"):
        parse_scenario(signals(group_9), "signals.yaml")


def test_two_approaches_sharing_a_mapem_lane_id_are_refused():
    def shared(intersection):
        intersection["approaches"][1]["ingress_lane_id"] = 1
    with pytest.raises(ScenarioError, match="ingress_lane_id and egress_lane_id must be its own lane id"):
        parse_scenario(signals(shared), "signals.yaml")


def test_an_approach_on_a_road_the_map_does_not_have_is_named():
    def elsewhere(intersection):
        intersection["approaches"][2]["road"] = "ring_road"
    config = parse_scenario(signals(elsewhere), "signals.yaml")
    with pytest.raises(ValueError, match="the map has no lane 0 on road 'ring_road'"):
        build_scenario(config, RoadMap.load(config.map))


def test_a_signal_fault_naming_a_unit_without_an_intersection_is_refused():
    data = yaml.safe_load(SIGNALS.read_text(encoding="utf-8"))
    data["faults"] = [{"type": "spat_loss", "unit_id": "rsu_c", "start_s": 10}]
    with pytest.raises(ScenarioError, match="faults.0.unit_id: no roadside unit 'rsu_c' with an intersection"):
        parse_scenario(data, "signals.yaml")


def test_a_spat_loss_in_the_scenario_silences_its_unit_from_its_start_to_its_end():
    data = yaml.safe_load(SIGNALS.read_text(encoding="utf-8"))
    data["faults"] = [{"type": "spat_loss", "unit_id": "rsu_a", "start_s": 1.0, "end_s": 3.0}]
    config = parse_scenario(data, "signals.yaml")
    sim = ScenarioSim(config, RoadMap.load(config.map), [])
    heard = {}
    for step in range(1, 201):
        sim.step(step * 0.02)
        for intent in sim.intents(step * 0.02):
            if intent.kind is IntentKind.SPATEM:
                heard.setdefault(intent.sender_id, []).append(intent.time_s)
    assert not [t for t in heard["rsu_a"] if 1.0 <= t < 3.0]
    assert max(heard["rsu_a"]) >= 3.0 and [t for t in heard["rsu_b"] if 1.0 <= t < 3.0]
