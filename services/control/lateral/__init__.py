"""Lateral control laws (pure logic, no bus)."""

from .controller import LateralController
from .types import LateralCommand, LateralLaw, PathState

__all__ = ["LateralCommand", "LateralController", "LateralLaw", "PathState"]
