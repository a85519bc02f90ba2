import enum

import pytest

from coopdrive.services.planner.engine import EngineEvent, Machine, MachineSpec, SpecError, StateSpec, Transition
from coopdrive.services.planner.graph import to_dot, to_mermaid


class S(enum.Enum):
    IDLE = enum.auto()
    WAIT = enum.auto()
    GO = enum.auto()
    SAFE = enum.auto()


class E(enum.Enum):
    ASK = enum.auto()
    ACK = enum.auto()


class Ctx:
    def __init__(self) -> None:
        self.allowed = True
        self.log: list[str] = []

    def allow(self) -> bool:
        return self.allowed

    def note_ack(self) -> None:
        self.log.append("ack")

    def enter_go(self) -> None:
        self.log.append("enter go")


def spec() -> MachineSpec:
    return MachineSpec("toy", S.IDLE, (
        StateSpec(S.IDLE, safe=True),
        StateSpec(S.WAIT, waiting=True, timeout_s=2.0, escape=S.SAFE),
        StateSpec(S.GO, terminal=True, on_enter=Ctx.enter_go),
        StateSpec(S.SAFE, safe=True),
    ), (
        Transition(S.IDLE, E.ASK, S.WAIT, reason="asked"),
        Transition(S.WAIT, E.ACK, S.GO, guard=Ctx.allow, action=Ctx.note_ack, reason="acknowledged"),
    ))


def started(ctx: Ctx | None = None, history_length: int = 32) -> Machine:
    m = Machine(spec(), ctx or Ctx(), history_length=history_length)
    m.start(0.0)
    return m


def test_an_event_fires_the_transition_runs_its_action_then_the_entry_action():
    m = started()
    assert m.dispatch(E.ASK, 1.0)
    assert m.dispatch(E.ACK, 1.5)
    assert m.state is S.GO and m.context.log == ["ack", "enter go"]
    assert m.last_transition().reason == "acknowledged" and m.last_transition().event == "ACK"


def test_a_false_guard_keeps_the_state_and_an_unknown_event_is_ignored():
    ctx = Ctx()
    ctx.allowed = False
    m = started(ctx)
    m.dispatch(E.ASK, 1.0)
    assert not m.dispatch(E.ACK, 1.1) and not m.dispatch(E.ASK, 1.2)
    assert m.state is S.WAIT


def test_time_in_state_counts_from_the_last_entry():
    m = started()
    m.dispatch(E.ASK, 3.0)
    assert m.time_in_state_s(4.5) == pytest.approx(1.5)


def test_a_waiting_state_escapes_to_its_safe_target_after_its_timeout_with_the_reason():
    m = started()
    m.dispatch(E.ASK, 1.0)
    assert not m.tick(2.9)
    assert m.tick(3.0)
    assert m.state is S.SAFE and m.is_safe_or_terminal()
    last = m.last_transition()
    assert last.event == EngineEvent.TIMEOUT.name and "timeout: 2 s in WAIT" in last.reason


def test_a_forced_transition_is_logged_with_who_and_runs_the_entry_action():
    m = started()
    m.force(S.GO, 5.0, who="safety driver", why="partner stuck")
    assert m.state is S.GO and m.context.log == ["enter go"]
    last = m.last_transition()
    assert last.forced and last.reason == "forced by safety driver: partner stuck"
    assert m.time_in_state_s(5.0) == 0.0


def test_the_history_keeps_only_the_most_recent_transitions():
    m = started(history_length=3)
    for i in range(5):
        m.force(S.IDLE, float(i), who="test")
    assert len(m.history) == 3 and m.history[-1].time_s == 4.0


def test_a_waiting_state_without_timeout_is_rejected():
    with pytest.raises(SpecError, match="WAIT needs a timeout"):
        MachineSpec("bad", S.IDLE, (StateSpec(S.IDLE), StateSpec(S.WAIT, waiting=True)), ())


def test_an_escape_to_an_unsafe_state_is_rejected():
    with pytest.raises(SpecError, match="not safe"):
        MachineSpec("bad", S.IDLE, (StateSpec(S.IDLE), StateSpec(S.WAIT, timeout_s=1.0, escape=S.IDLE)), ())


def test_a_transition_to_an_undeclared_state_is_rejected():
    with pytest.raises(SpecError, match="undeclared state GO"):
        MachineSpec("bad", S.IDLE, (StateSpec(S.IDLE),), (Transition(S.IDLE, E.ASK, S.GO),))


def test_mermaid_and_dot_exports_name_every_state_and_the_timeout_edge():
    mermaid, dot = to_mermaid(spec()), to_dot(spec())
    assert mermaid.startswith("stateDiagram-v2")
    for s in S:
        assert s.name in mermaid and f'"{s.name}"' in dot
    assert "WAIT --> SAFE: TIMEOUT 2 s" in mermaid
    assert '"WAIT" -> "SAFE" [label="TIMEOUT 2 s"]' in dot
    assert "GO --> [*]" in mermaid


def test_dispatch_first_fires_only_the_first_event_that_matches():
    m = started()
    assert m.dispatch_first([E.ACK, E.ASK, E.ACK], 1.0)
    assert m.state is S.WAIT and len(m.history) == 2
    assert not m.dispatch_first([E.ASK], 1.1)
