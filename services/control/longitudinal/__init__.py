"""Longitudinal control laws (pure logic, no bus)."""

from .controller import LongitudinalController
from .types import AccLaw, CaccLaw, FollowInput, LongitudinalCommand, Spacing, SpeedLaw, Target

__all__ = ["AccLaw", "CaccLaw", "FollowInput", "LongitudinalCommand", "LongitudinalController", "Spacing", "SpeedLaw", "Target"]
