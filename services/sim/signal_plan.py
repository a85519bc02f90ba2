"""Fixed-time signal plans of the simulator's traffic lights, as scenario files give them (pydantic).

A plan is a cycle of stages; in each stage one set of signal groups is green, then amber, then all red for the
clearance time before the next stage's groups get green. Stages are exclusive, so no two groups of different stages
are ever green (or amber) together: conflicting movements go in different stages. A stage may hold its green
longer while vehicles still arrive (actuated extension), up to max_extension_s.
"""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field, model_validator

# Amber of 3 s suits 50 km/h approaches (ITE's kinematic amber: t + v / 2a = 1 s + 13.9 / 6 = 3.3 s; RiLSA gives
# 3 s at 50 km/h). Red-amber of 1 s is the German and Austrian practice; 0 leaves it out.
DEFAULT_AMBER_S = 3.0
DEFAULT_RED_AMBER_S = 1.0
DEFAULT_ALL_RED_S = 2.0


class StrictFrozen(BaseModel):
    """A scenario file's part that takes no unknown key and does not change once read."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class SignalStage(StrictFrozen):
    # The signal groups (SPATEM/MAPEM signalGroup ids, 1..255) green in this stage.
    groups: list[int] = Field(min_length=1)
    green_s: float = Field(gt=0)
    # Actuated: the green is held while a vehicle is on a group's detector, this long at most (0: fixed time).
    max_extension_s: float = Field(default=0.0, ge=0)

    @model_validator(mode="after")
    def _groups_valid(self) -> SignalStage:
        if any(not 1 <= group <= 255 for group in self.groups):
            raise ValueError(f"groups: signal groups are 1..255, not {self.groups}")
        return self


class SignalPlan(StrictFrozen):
    stages: list[SignalStage] = Field(min_length=1)
    # Where the cycle starts (the first stage's green) on the run's clock: coordinated intersections differ by it.
    offset_s: float = 0.0
    amber_s: float = Field(default=DEFAULT_AMBER_S, gt=0)
    red_amber_s: float = Field(default=DEFAULT_RED_AMBER_S, ge=0)
    # All-red clearance between one stage's amber and the next stage's green.
    all_red_s: float = Field(default=DEFAULT_ALL_RED_S, gt=0)
    # Detectors of actuated stages: a vehicle this far or nearer before its stop line calls for an extension.
    detector_m: float = Field(default=40.0, gt=0)

    @model_validator(mode="after")
    def _consistent(self) -> SignalPlan:
        groups = [group for stage in self.stages for group in stage.groups]
        if len(set(groups)) != len(groups):
            raise ValueError("stages: a signal group may be green in one stage only")
        if self.red_amber_s > self.all_red_s:
            raise ValueError("red_amber_s: red-amber shows during the all-red clearance: at most all_red_s")
        if len(self.stages) == 1 and self.red_amber_s == self.all_red_s:
            raise ValueError("red_amber_s: a one-stage plan needs some red: less than all_red_s")
        return self

    @property
    def intergreen_s(self) -> float:
        return self.amber_s + self.all_red_s

    @property
    def cycle_s(self) -> float:
        return sum(stage.green_s for stage in self.stages) + len(self.stages) * self.intergreen_s

    @property
    def groups(self) -> list[int]:
        return sorted(group for stage in self.stages for group in stage.groups)
