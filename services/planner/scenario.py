"""What every scenario module offers the Planner."""

from __future__ import annotations

import enum
from typing import Protocol

from coopdrive.v1 import planner_pb2

from .engine import MachineSpec
from .situation import Situation


class ScenarioLogic(Protocol):
    """A scenario: its machine's spec, the events it sees in a step and the behaviour of each state.

    The scenario object is the machine's context: guards and actions are its methods.
    """

    spec: MachineSpec
    scenario: planner_pb2.Scenario

    def observe(self, sit: Situation, state: enum.Enum, time_in_state_s: float) -> list[enum.Enum]:
        """Takes this step's situation and returns the events seen, in the order to offer them."""

    def behaviour(self, state: enum.Enum) -> planner_pb2.BehaviourRequest:
        """The request for the state the machine is in after this step's transitions."""
