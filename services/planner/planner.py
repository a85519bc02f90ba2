"""The Planner: one scenario machine at a time, stepped with explicit times and inputs.

Deterministic: the same sequence of (now_s, inputs) gives the same requests, states and history.
"""

from __future__ import annotations

import enum
import math

from coopdrive.v1 import planner_pb2
from coopdrive.v2x.timebase import ItsClock

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
from .traffic_lights import TrafficLights

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
    """The scenario's machine, and beside it the traffic lights' (`traffic_lights.py`), which adds the signalised
    stop line and GLOSA's speed to the scenario's request. `clock` reads SPaT times (UTC) on the step's clock."""

    def __init__(self, config: PlannerLogicConfig | None = None, glosa: bool = True,
                 clock: ItsClock | None = None) -> None:
        self.config = config or PlannerLogicConfig()
        self.logic: ScenarioLogic | None = None
        self.machine: Machine | None = None
        self.lights = TrafficLights(self.config.signals, clock or ItsClock(), glosa)
        self.lights_machine = Machine(self.lights.spec, self.lights, history_length=self.config.history_length)
        self._graph_sent_s: float | None = None
        self._lights_graph_sent_s: float | None = None
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
        self._step_lights(now_s, sit, request)
        return request, self.state(now_s)

    def _step_lights(self, now_s: float, sit: Situation, request: planner_pb2.BehaviourRequest) -> None:
        """The traffic lights' machine, with the scenario's speed as the road's limit; then its additions."""
        machine = self.lights_machine
        if not machine.started:
            machine.start(now_s)
        for _ in range(MAX_TRANSITIONS_PER_STEP):
            if not machine.dispatch_first(self.lights.observe(sit, request.desired_speed_mps), now_s):
                break
        machine.tick(now_s)
        self.lights.apply(machine.state, request)

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
        message = self._state_of(self.machine, now_s, self._graph_sent_s)
        if message.graph_mermaid:
            self._graph_sent_s = now_s
        return message

    def lights_state(self, now_s: float) -> planner_pb2.PlannerState:
        """The traffic lights' machine as a PlannerState (after a step)."""
        message = self._state_of(self.lights_machine, now_s, self._lights_graph_sent_s)
        if message.graph_mermaid:
            self._lights_graph_sent_s = now_s
        return message

    def _state_of(self, machine: Machine, now_s: float, graph_sent_s: float | None) -> planner_pb2.PlannerState:
        message = planner_pb2.PlannerState(
            scenario=self.logic.scenario, machine=machine.spec.name, state=machine.state.name,
            time_in_state_s=machine.time_in_state_s(now_s), recent_transitions=list(machine.history))
        message.header.sample_time_s = now_s
        if graph_sent_s is None or now_s - graph_sent_s >= self.config.graph_period_s:
            message.graph_mermaid = to_mermaid(machine.spec)
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
