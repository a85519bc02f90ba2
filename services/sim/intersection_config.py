"""A signalised intersection as a scenario file gives it: where it is, its signal plan, and its approaches (which map
lane, where its stop line is, which signal group controls it and which MAPEM lane ids it gets)."""
from __future__ import annotations

from pydantic import Field, model_validator

from coopdrive.services.sim.signal_plan import SignalPlan, StrictFrozen

# MAPEM 1 Hz (the Berlin roadside unit of the issue sent 987 in 17 minutes) and SPATEM 10 Hz, as often as its
# TimeMarks (tenths of a second) can change; deployments differ (the same Berlin unit sent SPATEM about 0.5 Hz), so
# both are the scenario's to set.
DEFAULT_MAPEM_RATE_HZ = 1.0
DEFAULT_SPATEM_RATE_HZ = 10.0
# A MAPEM's ingress lane reaches this far back from its stop line: far enough to slow down from 50 km/h and for
# a speed advisory to act on; its egress lane this far past the box.
DEFAULT_APPROACH_LENGTH_M = 250.0
DEFAULT_EXIT_LENGTH_M = 50.0
# LaneID (0..255) and ApproachID (0..15) ranges of TS 103 301; signal groups 1..255 (0 is "not available").
MAX_LANE_ID = 255
MAX_APPROACH_ID = 15


class SignalApproach(StrictFrozen):
    road: str = Field(min_length=1)
    lane: int = Field(ge=0)
    # Station on the map lane of the stop line; the lane enters the intersection's box there.
    stop_station_m: float = Field(ge=0)
    # From the stop line to where the lane leaves the box: its egress lane starts there.
    box_length_m: float = Field(gt=0)
    signal_group: int = Field(ge=1, le=255)
    ingress_lane_id: int = Field(ge=1, le=MAX_LANE_ID)
    egress_lane_id: int = Field(ge=1, le=MAX_LANE_ID)
    approach_length_m: float = Field(default=DEFAULT_APPROACH_LENGTH_M, gt=0)
    exit_length_m: float = Field(default=DEFAULT_EXIT_LENGTH_M, gt=0)


class SignalisedIntersection(StrictFrozen):
    intersection_id: int = Field(ge=0, le=65535)
    region: int | None = Field(default=None, ge=0, le=65535)
    name: str = ""
    # The intersection's reference point (ENU metres of the map): every lane's first node is an offset from it.
    x_m: float
    y_m: float
    # MAPEM revision (MsgCount): raised when the map changes.
    revision: int = Field(default=1, ge=0, le=127)
    plan: SignalPlan
    approaches: list[SignalApproach] = Field(min_length=1, max_length=MAX_APPROACH_ID)
    mapem_rate_hz: float = Field(default=DEFAULT_MAPEM_RATE_HZ, gt=0)
    spatem_rate_hz: float = Field(default=DEFAULT_SPATEM_RATE_HZ, gt=0)

    @model_validator(mode="after")
    def _consistent(self) -> SignalisedIntersection:
        lane_ids = [i for a in self.approaches for i in (a.ingress_lane_id, a.egress_lane_id)]
        if len(set(lane_ids)) != len(lane_ids):
            raise ValueError("approaches: every ingress_lane_id and egress_lane_id must be its own lane id")
        missing = sorted({a.signal_group for a in self.approaches} - set(self.plan.groups))
        if missing:
            raise ValueError(f"approaches: signal groups {missing} are in no stage of the plan")
        return self
