"""Scripted speed profiles (constant, piecewise linear, sinusoid) and lane changes, usable in scenario YAML."""
from __future__ import annotations

import math
from typing import Annotated, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, model_validator


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class ConstantSpeed(_Strict):
    kind: Literal["constant"] = "constant"
    speed_mps: float = Field(ge=0)

    def speed_at(self, time_s: float) -> float:
        return self.speed_mps


class SpeedPoint(_Strict):
    time_s: float
    speed_mps: float = Field(ge=0)


class PiecewiseSpeed(_Strict):
    """Linear between points, held before the first and after the last."""

    kind: Literal["piecewise"] = "piecewise"
    points: list[SpeedPoint] = Field(min_length=1)

    @model_validator(mode="after")
    def _times_increase(self) -> PiecewiseSpeed:
        times = [p.time_s for p in self.points]
        if any(b <= a for a, b in zip(times, times[1:])):
            raise ValueError("points must have strictly increasing time_s")
        return self

    def speed_at(self, time_s: float) -> float:
        return float(np.interp(time_s, [p.time_s for p in self.points], [p.speed_mps for p in self.points]))


class SinusoidSpeed(_Strict):
    """mean + amplitude sin(2 pi f (t - start)) from start_s on, mean before (the string stability test)."""

    kind: Literal["sinusoid"] = "sinusoid"
    mean_speed_mps: float = Field(ge=0)
    amplitude_mps: float = Field(ge=0)
    frequency_hz: float = Field(gt=0)
    start_s: float = 0.0
    # Number of whole periods; 0 keeps oscillating.
    periods: int = Field(default=0, ge=0)
    # A hard brake to standstill from this time on (the string scenario's end), at brake_decel_mps2.
    brake_at_s: float | None = Field(default=None, ge=0)
    brake_decel_mps2: float = Field(default=6.0, gt=0)

    def speed_at(self, time_s: float) -> float:
        if self.brake_at_s is not None and time_s > self.brake_at_s:
            return max(self._oscillating(self.brake_at_s) - self.brake_decel_mps2 * (time_s - self.brake_at_s), 0.0)
        return self._oscillating(time_s)

    def _oscillating(self, time_s: float) -> float:
        elapsed_s = time_s - self.start_s
        if elapsed_s < 0.0 or (self.periods and elapsed_s > self.periods / self.frequency_hz):
            return self.mean_speed_mps
        return max(self.mean_speed_mps + self.amplitude_mps * math.sin(2.0 * math.pi * self.frequency_hz * elapsed_s),
                   0.0)


SpeedProfile = Annotated[Union[ConstantSpeed, PiecewiseSpeed, SinusoidSpeed], Field(discriminator="kind")]


class LaneChange(_Strict):
    start_s: float = Field(ge=0)
    target_lane: int = Field(ge=0)
    duration_s: float = Field(default=6.0, gt=0)


def smoothstep(share: float) -> float:
    """Quintic 0 -> 1 with zero slope and curvature at both ends (a smooth lateral move)."""
    x = min(max(share, 0.0), 1.0)
    return x * x * x * (10.0 - 15.0 * x + 6.0 * x * x)
