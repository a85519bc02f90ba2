"""Configuration of the control service's logic (the integrator's service.py reads it)."""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field

from .lateral.types import LateralLaw
from .longitudinal.types import AccLaw, CaccLaw, SpeedLaw
from coopdrive.vehicle import VehicleKind

from .profiles import PROFILES, VehicleProfile


class LaneSourceChoice(enum.Enum):
    """Which lane lateral control steers in."""

    # The scene's lane (map and camera fused, or the camera alone where they disagree) while it is fresh and
    # from the camera; otherwise the map's lane at the estimated position.
    SCENE = "scene"
    # Only the map's lane at the estimated position (the GCDC vehicles' way: Heudiasyc's lateral control).
    MAP = "map"


class ControlConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # The vehicle driven (its profile, profiles.PROFILES); `profile_overrides` patches the profile's fields, e.g.
    # {"vehicle": {"response_time_constant_s": 0.4}} or {"spacing": {"time_gap_s": 1.2}}.
    vehicle: VehicleKind = VehicleKind.PASSENGER_CAR
    profile_overrides: dict = Field(default_factory=dict)
    cacc_law: CaccLaw = CaccLaw.OURS
    acc_law: AccLaw = AccLaw.OURS
    speed_law: SpeedLaw = SpeedLaw.PI
    lateral_law: LateralLaw = LateralLaw.HEUDIASYC_PD
    period_s: float = Field(0.02, gt=0)
    lane_source: LaneSourceChoice = LaneSourceChoice.SCENE
    # A scene lane older than this (two scene periods and a bit) is not steered by.
    scene_lane_max_age_s: float = Field(0.1, gt=0)

    def vehicle_profile(self) -> VehicleProfile:
        base = PROFILES[self.vehicle]
        if not self.profile_overrides:
            return base
        return VehicleProfile.model_validate(_merged(base.model_dump(), self.profile_overrides))


def _merged(base: dict, overrides: dict) -> dict:
    """base with overrides on it, section by section."""
    return {key: _merged(value, overrides[key]) if isinstance(value, dict) and isinstance(overrides.get(key), dict)
            else overrides.get(key, value) for key, value in base.items()} | {
        key: value for key, value in overrides.items() if key not in base}
