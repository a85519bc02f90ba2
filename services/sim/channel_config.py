"""Configuration of the simulated ITS-G5 radio channel."""
from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class GilbertElliottConfig(BaseModel):
    """Two-state burst loss per link, stepped once per packet on that link (Gilbert 1960, Elliott 1963). The
    defaults lose about 3 % of packets, in bursts of about three (1 / bad_to_good_probability) at a CAM's 10 Hz."""

    model_config = ConfigDict(extra="forbid")

    good_to_bad_probability: float = Field(default=0.01, ge=0, le=1)
    bad_to_good_probability: float = Field(default=0.3, gt=0, le=1)
    loss_in_good_probability: float = Field(default=0.01, ge=0, le=1)
    loss_in_bad_probability: float = Field(default=0.7, ge=0, le=1)

    @property
    def bad_state_share(self) -> float:
        """Stationary probability of the bad state, p_gb / (p_gb + p_bg)."""
        total = self.good_to_bad_probability + self.bad_to_good_probability
        return self.good_to_bad_probability / total

    @property
    def mean_loss_probability(self) -> float:
        bad = self.bad_state_share
        return bad * self.loss_in_bad_probability + (1.0 - bad) * self.loss_in_good_probability


class RadioChannelConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    base_latency_s: float = Field(default=0.002, ge=0)
    # Standard deviation of a half-normal delay added to the base latency.
    jitter_s: float = Field(default=0.001, ge=0)
    # Distance loss is logistic: 50 % at half_loss_distance_m, the transition about distance_scale_m wide.
    half_loss_distance_m: float = Field(default=500.0, gt=0)
    distance_scale_m: float = Field(default=60.0, gt=0)
    max_range_m: float = Field(default=1000.0, gt=0)
    burst: GilbertElliottConfig = GilbertElliottConfig()
    corruption_probability: float = Field(default=0.0, ge=0, le=1)
