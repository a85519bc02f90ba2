"""The contracts the interchangeable longitudinal laws keep, so the controller never asks which law it holds.

A following law (our CACC, Ploeg's CACC, dCACC, our ACC, Rajamani's ACC) turns a FollowInput into an acceleration;
a cruise law (the cruise PI, DRIVERTIVE's static law) drives to the planner's desired speed and is engaged only
while it is the law that commands.
"""

from __future__ import annotations

from typing import Protocol

from .types import FollowInput


class FollowingLaw(Protocol):
    def reset(self, command_mps2: float, f: FollowInput) -> None:
        """Bumpless start from the command applied now, in the situation f."""

    def step(self, dt_s: float, f: FollowInput) -> float:
        """The acceleration request (m/s2) for this period."""


class CruiseLaw(Protocol):
    engaged: bool

    def reset(self, command_mps2: float, ego_speed_mps: float) -> None:
        """Bumpless start from the applied command at the present speed."""

    def engage(self, command_mps2: float, ego_speed_mps: float) -> None:
        """It commands from now on (it won the min-select)."""

    def disengage(self) -> None:
        """Another law commands."""

    def step(self, dt_s: float, ego_speed_mps: float, desired_speed_mps: float) -> float:
        """The acceleration request (m/s2) toward the desired speed."""

    def track(self, dt_s: float, applied_mps2: float) -> None:
        """While engaged: follow the command actually applied (after shaping), against wind-up."""
