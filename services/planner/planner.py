"""The Planner: one scenario machine at a time, stepped with explicit times and inputs.

Deterministic: the same sequence of (now_s, inputs) gives the same requests, states and history.
"""

from __future__ import annotations

import enum
import math

from coopdrive.v1 import planner_pb2

from .config import PlannerLogicConfig
from .emergency import EmergencyScenario
from .engine import Machine
from .graph import to_mermaid
from .inputs import PlannerInputs
from .intersection import IntersectionScenario
from .merge import MergeScenario
from .platooning import PlatooningScenario
from .scenario import ScenarioLogic
from .situation import Situation

# Transitions one step may chain (IDLE -> APPROACH -> CROSSING when the RSU starts us inside the zone).
MAX_TRANSITIONS_PER_STEP = 8


class PlannerInputError(ValueError):
    """The step's inputs cannot be planned with; the message names what was wrong."""


def make_scenario(scenario: int, config: PlannerLogicConfig) -> ScenarioLogic:
    """The scenario logic for a Scenario enum value; following (and unspecified) is the emergency machine's
    NORMAL driving, so a corridor is opened whatever the scenario."""
    if scenario == planner_pb2.SCENARIO_PLATOON:
        return PlatooningScenario(config)
    if scenario == planner_pb2.SCENARIO_MERGE:
        return MergeScenario(config)
    if scenario == planner_pb2.SCENARIO_INTERSECTION:
        return IntersectionScenario(config)
    return EmergencyScenario(config, scenario if scenario else planner_pb2.SCENARIO_FOLLOW)


class Planner:
    def __init__(self, config: PlannerLogicConfig | None = None) -> None:
        self.config = config or PlannerLogicConfig()
        self.logic: ScenarioLogic | None = None
        self.machine: Machine | None = None
        self._graph_sent_s: float | None = None
        self._last: tuple[float, PlannerInputs] | None = None
        # Steps refused for bad inputs (PlannerInputError), for the service's counters.
        self.input_errors = 0

    def step(self, now_s: float, inputs: PlannerInputs
             ) -> tuple[planner_pb2.BehaviourRequest, planner_pb2.PlannerState]:
        """Events first (so a success beats a timeout in the same step), then timeouts, then the behaviour.

        Raises PlannerInputError (and counts it in `input_errors`) for inputs it cannot plan with; the
        machine is then left as it was.
        """
        self._check(now_s, inputs)
        self._ensure_machine(now_s, inputs.scenario)
        sit = Situation(now_s, inputs, self.config)
        machine = self.machine
        # One transition per look: after each, the scenario looks again from the new state (its entry
        # action may have changed what it watches, e.g. the partner), up to a bound against livelock.
        for _ in range(MAX_TRANSITIONS_PER_STEP):
            events = self.logic.observe(sit, machine.state, machine.time_in_state_s(now_s))
            if not machine.dispatch_first(events, now_s):
                break
        machine.tick(now_s)
        self._last = (now_s, inputs)
        request = self.logic.behaviour(machine.state)
        return request, self.state(now_s)

    def _check(self, now_s: float, inputs: PlannerInputs) -> None:
        problem = ""
        if not math.isfinite(now_s):
            problem = f"now_s is not finite: {now_s}"
        elif self._last is not None and now_s < self._last[0]:
            problem = f"time went backwards: now_s {now_s} < previous step {self._last[0]}"
        elif inputs.station_id <= 0:
            problem = f"own station_id must be positive, got {inputs.station_id}"
        elif inputs.scenario not in planner_pb2.Scenario.values():
            problem = f"unknown scenario value {inputs.scenario}"
        if problem:
            self.input_errors += 1
            raise PlannerInputError(problem)

    def force(self, state_name: str, now_s: float, who: str, why: str = "") -> None:
        """Operator supervision (Heudiasyc HMI): put the machine in a state by name; logged as forced."""
        if self.machine is None:
            raise RuntimeError("the planner has not stepped yet: no machine to force")
        target = self.machine.spec.state_by_name(state_name)
        if self._last is not None:
            self.logic.observe(Situation(now_s, self._last[1], self.config), self.machine.state,
                               self.machine.time_in_state_s(now_s))
        self.machine.force(target, now_s, who, why)

    @property
    def state_name(self) -> str:
        return self.machine.state.name if self.machine is not None else ""

    def current_state(self) -> enum.Enum | None:
        return self.machine.state if self.machine is not None else None

    def state(self, now_s: float) -> planner_pb2.PlannerState:
        machine = self.machine
        message = planner_pb2.PlannerState(
            scenario=self.logic.scenario, machine=machine.spec.name, state=machine.state.name,
            time_in_state_s=machine.time_in_state_s(now_s), recent_transitions=list(machine.history))
        message.header.sample_time_s = now_s
        if self._graph_sent_s is None or now_s - self._graph_sent_s >= self.config.graph_period_s:
            message.graph_mermaid = to_mermaid(machine.spec)
            self._graph_sent_s = now_s
        return message

    def _ensure_machine(self, now_s: float, scenario: int) -> None:
        if self.logic is not None and self.logic.scenario == scenario:
            return
        if self.logic is not None and scenario == planner_pb2.SCENARIO_UNSPECIFIED \
                and self.logic.scenario == planner_pb2.SCENARIO_FOLLOW:
            return
        previous = self.machine
        self.logic = make_scenario(scenario, self.config)
        self.machine = Machine(self.logic.spec, self.logic, history_length=self.config.history_length)
        if previous is not None:
            # Keep the old machine's story so the HMI sees why the scenario changed.
            self.machine.history.extend(previous.history)
        self._graph_sent_s = None
        self.machine.start(now_s)
