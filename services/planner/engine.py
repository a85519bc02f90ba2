"""A small state-machine engine: machines declared as data, run with explicit times.

A machine is a `MachineSpec` (states, transitions, per-state timeouts with an escape target); a
`Machine` runs one spec for one context object that guards and actions receive. Nothing here
reads a clock: every call takes `now_s`, so runs are deterministic and replayable.
"""

from __future__ import annotations

import enum
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Callable, Generic, TypeVar

from coopdrive.v1 import planner_pb2

C = TypeVar("C")
Guard = Callable[[Any], bool]
Action = Callable[[Any], None]

DEFAULT_HISTORY_LENGTH = 32


class EngineEvent(enum.Enum):
    """Events the engine raises itself rather than the scenario."""

    TIMEOUT = "timeout"
    FORCED = "forced"
    START = "start"


class SpecError(ValueError):
    """The declaration of a machine is inconsistent."""


@dataclass(frozen=True)
class StateSpec:
    state: enum.Enum
    # A waiting state depends on someone else; it must declare a timeout and an escape.
    waiting: bool = False
    timeout_s: float | None = None
    escape: enum.Enum | None = None
    # A safe state needs nobody's cooperation to stay safe (keep lane, follow the MIO).
    safe: bool = False
    terminal: bool = False
    on_enter: Action | None = None
    description: str = ""


@dataclass(frozen=True)
class Transition:
    source: enum.Enum
    event: enum.Enum
    target: enum.Enum
    guard: Guard | None = None
    action: Action | None = None
    # Why this transition fires, copied into the StateTransition's reason.
    reason: str = ""


@dataclass(frozen=True)
class MachineSpec:
    name: str
    initial: enum.Enum
    states: tuple[StateSpec, ...]
    transitions: tuple[Transition, ...]

    def __post_init__(self) -> None:
        names = {s.state for s in self.states}
        if len(names) != len(self.states):
            raise SpecError(f"{self.name}: a state is declared twice")
        if self.initial not in names:
            raise SpecError(f"{self.name}: initial state {self.initial.name} is not declared")
        by_state = {s.state: s for s in self.states}
        for spec in self.states:
            if spec.timeout_s is not None and spec.escape is None:
                raise SpecError(f"{self.name}: {spec.state.name} has a timeout but no escape target")
            if spec.waiting and (spec.timeout_s is None or spec.escape is None):
                raise SpecError(f"{self.name}: waiting state {spec.state.name} needs a timeout and an escape")
            if spec.escape is not None:
                target = by_state.get(spec.escape)
                if target is None:
                    raise SpecError(f"{self.name}: escape {spec.escape.name} of {spec.state.name} is not declared")
                if not (target.safe or target.terminal):
                    raise SpecError(f"{self.name}: escape {spec.escape.name} of {spec.state.name} is not safe")
        for t in self.transitions:
            for end in (t.source, t.target):
                if end not in names:
                    raise SpecError(f"{self.name}: transition uses undeclared state {end.name}")

    def state_spec(self, state: enum.Enum) -> StateSpec:
        for spec in self.states:
            if spec.state is state:
                return spec
        raise KeyError(state)

    def state_by_name(self, name: str) -> enum.Enum:
        for spec in self.states:
            if spec.state.name == name:
                return spec.state
        raise KeyError(f"{self.name} has no state {name!r}")


@dataclass
class Machine(Generic[C]):
    """One running instance of a spec; `context` is handed to guards, actions and entry actions."""

    spec: MachineSpec
    context: C
    history_length: int = DEFAULT_HISTORY_LENGTH
    state: enum.Enum | None = None
    entered_s: float = 0.0
    history: deque = field(default_factory=deque)

    def __post_init__(self) -> None:
        self.history = deque(maxlen=self.history_length)

    @property
    def started(self) -> bool:
        return self.state is not None

    def start(self, now_s: float) -> None:
        self._enter(self.spec.initial, now_s, EngineEvent.START, "machine started", forced=False, source=None)

    def time_in_state_s(self, now_s: float) -> float:
        return max(0.0, now_s - self.entered_s)

    def current(self) -> StateSpec:
        if self.state is None:
            raise RuntimeError(f"{self.spec.name} is not started")
        return self.spec.state_spec(self.state)

    def is_safe_or_terminal(self) -> bool:
        current = self.current()
        return current.safe or current.terminal

    def dispatch(self, event: enum.Enum, now_s: float) -> bool:
        """Fires the first transition from the current state on `event` whose guard holds."""
        for t in self.spec.transitions:
            if t.source is not self.state or t.event is not event:
                continue
            if t.guard is not None and not t.guard(self.context):
                continue
            if t.action is not None:
                t.action(self.context)
            self._enter(t.target, now_s, event, t.reason or event.name.lower(), forced=False, source=self.state)
            return True
        return False

    def dispatch_first(self, events: list[enum.Enum], now_s: float) -> bool:
        """Offers the events in order until one fires a transition; the rest were seen from the old state."""
        return any(self.dispatch(event, now_s) for event in events)

    def tick(self, now_s: float) -> bool:
        """Escapes from the current state if it has been in it longer than its timeout."""
        current = self.current()
        if current.timeout_s is None or self.time_in_state_s(now_s) < current.timeout_s:
            return False
        reason = f"timeout: {current.timeout_s:g} s in {current.state.name}"
        self._enter(current.escape, now_s, EngineEvent.TIMEOUT, reason, forced=False, source=self.state)
        return True

    def force(self, target: enum.Enum, now_s: float, who: str, why: str = "") -> None:
        """Operator supervision: go to `target` whatever the guards say; the entry actions still run."""
        self.spec.state_spec(target)
        reason = f"forced by {who}" + (f": {why}" if why else "")
        self._enter(target, now_s, EngineEvent.FORCED, reason, forced=True, source=self.state)

    def _enter(self, target: enum.Enum, now_s: float, event: enum.Enum, reason: str, forced: bool,
               source: enum.Enum | None) -> None:
        self.history.append(planner_pb2.StateTransition(
            time_s=now_s, from_state=source.name if source is not None else "", to_state=target.name,
            event=event.name, reason=reason, forced=forced))
        self.state, self.entered_s = target, now_s
        on_enter = self.spec.state_spec(target).on_enter
        if on_enter is not None:
            on_enter(self.context)

    def last_transition(self) -> planner_pb2.StateTransition | None:
        return self.history[-1] if self.history else None


def from_each(sources: list[enum.Enum], event: enum.Enum, target: enum.Enum, reason: str,
              guard: Guard | None = None, action: Action | None = None) -> tuple[Transition, ...]:
    """The same transition from several states (scenario end, lost partner)."""
    return tuple(Transition(s, event, target, guard=guard, action=action, reason=reason)
                 for s in sources if s is not target)
