"""Drivers: put a fresh Planner in a state by real inputs, then fire one declared transition with real inputs.

A `Reach` is the prelude for one source state: the steps (time, world arguments) that bring a fresh planner
there; the last step's world keeps it there. `on_event` and `on_timeout` make a driver from it: a
function of no arguments that runs the planner and returns the step's (BehaviourRequest, PlannerState) in
which the transition fired. Each machine's drivers module maps every declared transition, keyed
(machine, from, event, to) with event TIMEOUT for an escape, to its driver.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable

from planner_world import DT_S, planner

from coopdrive.services.planner.engine import EngineEvent
from coopdrive.services.planner.inputs import PlannerInputs
from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import planner_pb2

Key = tuple[str, str, str, str]
Driven = tuple[planner_pb2.BehaviourRequest, planner_pb2.PlannerState]
Driver = Callable[[], Driven]
TIMEOUT = EngineEvent.TIMEOUT.name
# A timeout driver steps this long after the timeout, so that no rounding of entry time plus timeout falls short.
PAST_TIMEOUT_S = 0.001


@dataclass(frozen=True)
class Reach:
    """How a fresh planner gets to a state: `world(t, **kwargs)` stepped at each (t, kwargs) of `steps`."""

    world: Callable[..., PlannerInputs]
    steps: tuple[tuple[float, dict], ...]
    # PlannerLogicConfig overrides of the planner that runs it.
    config: dict = field(default_factory=dict)

    @property
    def reached_s(self) -> float:
        return self.steps[-1][0]

    @property
    def steady(self) -> dict:
        """The world of the last step, which keeps the planner in the state reached."""
        return self.steps[-1][1]

    def then(self, t: float, **kwargs) -> Reach:
        """This prelude and one more step: the way to a next state."""
        return replace(self, steps=(*self.steps, (t, kwargs)))

    def run(self, p: Planner | None = None) -> tuple[Planner, Driven]:
        p = p or planner(**self.config)
        for t, kwargs in self.steps:
            driven = p.step(t, self.world(t, **kwargs))
        return p, driven

    def step(self, p: Planner, t: float, **change) -> Driven:
        """One step at t with the steady world, changed by `change`."""
        return p.step(t, self.world(t, **{**self.steady, **change}))


def on_event(reach: Reach, after_s: float = DT_S, **change) -> Driver:
    """The source state reached, one step `after_s` later with the steady world changed by `change`."""
    def drive() -> Driven:
        p, _ = reach.run()
        return reach.step(p, round(reach.reached_s + after_s, 6), **change)
    return drive


def on_timeout(reach: Reach) -> Driver:
    """The source state reached, the steady world stepped just after its timeout has passed since the entry."""
    def drive() -> Driven:
        p, _ = reach.run()
        timeout_s = p.machine.current().timeout_s
        return reach.step(p, round(p.machine.entered_s + timeout_s + PAST_TIMEOUT_S, 6))
    return drive


def fired(state: planner_pb2.PlannerState, source: str, event: str, target: str
          ) -> planner_pb2.StateTransition | None:
    """The transition source -event-> target of the step `state` reports, if it fired (not forced) in it."""
    return next((t for t in state.recent_transitions
                 if t.time_s == state.header.sample_time_s and not t.forced
                 and (t.from_state, t.event, t.to_state) == (source, event, target)), None)
