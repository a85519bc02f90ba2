"""Configuration of the control service's logic (the integrator's service.py reads it)."""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field

from .lateral.types import LateralLaw
from .longitudinal.types import AccLaw, CaccLaw, SpeedLaw
from .profiles import VehicleProfile, profile_by_name


class LaneSourceChoice(enum.Enum):
    """Which lane lateral control steers in."""

    # The scene's lane (map and camera fused, or the camera alone where they disagree) while it is fresh and
    # from the camera; otherwise the map's lane at the estimated position.
    SCENE = "scene"
    # Only the map's lane at the estimated position (the GCDC vehicles' way: Heudiasyc's lateral control).
    MAP = "map"


class ControlConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # "car" or "truck" (profiles.PROFILES); `profile_overrides` patches fields, e.g. {"engine_lag_s": 0.4}.
    profile: str = "car"
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
        base = profile_by_name(self.profile)
        if not self.profile_overrides:
            return base
        return VehicleProfile.model_validate({**base.model_dump(), **self.profile_overrides})
