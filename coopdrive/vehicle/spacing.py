"""SpacingPolicy: the gap a following vehicle keeps, r + h v (constant time gap: Heudiasyc eq. 4, the GCDC 2016
rules' safety distance plus headway), in one home for the planner that requests it, control that falls back on it
and the string-stability analysis that judges it."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field


class SpacingPolicy(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    # Heudiasyc's r ("typically 6 meters").
    standstill_m: float = Field(6.0, ge=0)
    # With V2V (CACC): the platoons' gap, which the planner requests and every run drives.
    cacc_time_gap_s: float = Field(0.5, gt=0)
    # The predecessor's acceleration estimated from radar alone (dCACC, Ploeg et al. 2015's degradation).
    dcacc_time_gap_s: float = Field(1.0, gt=0)
    # Without V2V (ACC): Heudiasyc's "typically 1.5 seconds".
    acc_time_gap_s: float = Field(1.5, gt=0)


SPACING = SpacingPolicy()
