from pathlib import Path

import pytest
from planner_world import ego, inputs, planner, rsu_start, scene

from coopdrive.services.planner.config import PlannerLogicConfig
from coopdrive.services.planner.engine import MachineSpec
from coopdrive.services.planner.export_graphs import machine_specs, markdown, with_readme_block
from coopdrive.services.planner.graph import to_mermaid
from coopdrive.services.planner.planner import PlannerInputError
from coopdrive.v1 import planner_pb2

DOCS = Path(__file__).resolve().parents[2] / "docs" / "planner.md"


def platoon_inputs(t):
    return inputs(planner_pb2.SCENARIO_PLATOON, ego=ego(), scene=scene(), iclcms={900: rsu_start(t)})


def test_the_same_inputs_give_the_same_requests_and_states():
    runs = []
    for _ in range(2):
        p = planner()
        runs.append([tuple(m.SerializeToString(deterministic=True) for m in p.step(0.1 * i, platoon_inputs(0.1 * i)))
                     for i in range(20)])
    assert runs[0] == runs[1]


def test_a_new_scenario_switches_the_machine_and_keeps_the_history():
    p = planner()
    p.step(0.0, platoon_inputs(0.0))
    _, state = p.step(0.1, inputs(planner_pb2.SCENARIO_MERGE, ego=ego(), scene=scene()))
    assert state.machine == "merge" and state.state == "IDLE" and state.scenario == planner_pb2.SCENARIO_MERGE
    assert [t.to_state for t in state.recent_transitions][:2] == ["IDLE", "JOINING"]


def test_forcing_an_unknown_state_names_it():
    p = planner()
    p.step(0.0, platoon_inputs(0.0))
    with pytest.raises(KeyError, match="no state 'FLYING'"):
        p.force("FLYING", 0.1, who="operator")


def test_forcing_before_the_first_step_is_refused():
    with pytest.raises(RuntimeError, match="not stepped"):
        planner().force("IDLE", 0.0, who="operator")


def test_the_mermaid_graph_is_attached_at_its_low_rate():
    p = planner(graph_period_s=1.0)
    sent = [bool(p.step(0.1 * i, platoon_inputs(0.1 * i))[1].graph_mermaid) for i in range(21)]
    assert sent.count(True) == 3 and sent[0] and sent[10] and sent[20]
    assert p.state_name


@pytest.mark.parametrize("spec", machine_specs(), ids=lambda s: s.name)
def test_the_mermaid_export_contains_every_state(spec: MachineSpec):
    text = to_mermaid(spec)
    for s in spec.states:
        assert f"state \"{s.state.name}\" as {s.state.name}" in text
    assert f"```mermaid\n{text}```" in markdown()


@pytest.mark.parametrize("spec", machine_specs(), ids=lambda s: s.name)
def test_every_state_that_is_not_safe_has_a_timeout_and_the_unsafe_states_form_no_cycle(spec: MachineSpec):
    unsafe = {s.state for s in spec.states if not (s.safe or s.terminal)}
    assert all(spec.state_spec(s).timeout_s is not None for s in unsafe)
    edges = {(t.source, t.target) for t in spec.transitions if t.source in unsafe and t.target in unsafe}
    remaining = set(unsafe)
    while remaining:
        sources = {s for s in remaining if not any(a in remaining and b == s for a, b in edges)}
        assert sources, f"{spec.name}: unsafe states cycle among {sorted(s.name for s in remaining)}"
        remaining -= sources


def test_the_docs_page_is_what_the_export_script_writes():
    with open(DOCS, encoding="utf-8") as f:
        assert f.read() == markdown(PlannerLogicConfig())


@pytest.mark.parametrize("now_s, station_id, scenario, message", [
    (float("nan"), 100, planner_pb2.SCENARIO_PLATOON, "not finite"),
    (0.5, 0, planner_pb2.SCENARIO_PLATOON, "station_id must be positive"),
    (0.5, 100, 42, "unknown scenario value 42"),
    (0.05, 100, planner_pb2.SCENARIO_PLATOON, "time went backwards"),
])
def test_bad_inputs_are_refused_with_a_clear_error_and_counted(now_s, station_id, scenario, message):
    p = planner()
    p.step(0.1, platoon_inputs(0.1))
    bad = platoon_inputs(now_s)
    bad.station_id, bad.scenario = station_id, scenario
    with pytest.raises(PlannerInputError, match=message):
        p.step(now_s, bad)
    assert p.input_errors == 1 and p.state_name == "JOINING"


def test_the_planner_page_shows_every_machine_graph_as_generated():
    page = (Path(__file__).resolve().parents[2] / "docs" / "planner.md").read_text(encoding="utf-8")
    assert page == markdown(), "docs/planner.md is stale: python -m coopdrive.services.planner.export_graphs " \
                               "--output docs/planner.md"
    assert all(f"%% machine {spec.name}" in page for spec in machine_specs())


def test_a_readme_without_the_graph_markers_is_refused_with_their_names():
    with pytest.raises(ValueError, match="planner-graphs:begin"):
        with_readme_block("# a README\n")
