"""Configuration of the planner service (PlannerConfig) and of its scenario logic."""

from __future__ import annotations

import enum

from pydantic import AwareDatetime, BaseModel, ConfigDict, Field, model_validator

from coopdrive.messages.unknowns import DEFAULT_LENGTH_M
from coopdrive.runtime.service import ServiceConfig
from coopdrive.v1 import planner_pb2
from coopdrive.vehicle import SPACING

KPH = 1.0 / 3.6


class Intention(enum.IntEnum):
    """iCLCM intention at the intersection (values equal the wire and its_pb2.Intention codes)."""

    STRAIGHT = 1
    LEFT = 2
    RIGHT = 3


class PlatoonConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    platoon_a_speed_mps: float = Field(80.0 * KPH, gt=0)
    platoon_b_speed_mps: float = Field(60.0 * KPH, gt=0)
    # With V2V (CACC) and without it (ACC fallback, larger gap, Ploeg et al. 2015 degradation).
    cacc_time_gap_s: float = Field(SPACING.cacc_time_gap_s, gt=0)
    acc_time_gap_s: float = Field(SPACING.acc_time_gap_s, gt=0)
    leave_time_gap_s: float = Field(2.5, gt=0)
    join_gap_tolerance_m: float = Field(3.0, gt=0)
    # A member may go this much faster than its own cruise speed to keep up with its partner: a follower
    # capped at the leader's top speed falls behind on every crest of a speed wave and passes a slower wave on.
    member_speed_headroom_mps: float = Field(3.0, ge=0)
    join_timeout_s: float = Field(30.0, gt=0)
    leave_timeout_s: float = Field(15.0, gt=0)


# A passenger car's length: ours unless configured, and that of a car the scene gives no length for (the length
# every reader of the scene assumes then).
TYPICAL_CAR_LENGTH_M = DEFAULT_LENGTH_M


class MergeConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # 0 = rightmost lane; GCDC: platoon A left at 80 km/h, B right at 60 km/h, both slow to 40 km/h.
    lane_a_index: int = 1
    lane_b_index: int = 0
    merge_speed_mps: float = Field(40.0 * KPH, gt=0)
    pairing_timeout_s: float = Field(5.0, gt=0)
    head_flag_timeout_s: float = Field(60.0, gt=0)
    gap_making_timeout_s: float = Field(20.0, gt=0)
    stom_timeout_s: float = Field(10.0, gt=0)
    merge_wait_timeout_s: float = Field(15.0, gt=0)
    lane_change_duration_s: float = Field(6.0, gt=0)
    # Heudiasyc: lane change done in < 10 s.
    lane_change_timeout_s: float = Field(12.0, gt=0)
    # Gap asked of the gap maker on top of the spacing policy, for the merging car's length.
    merge_extra_gap_m: float = Field(6.0, ge=0)
    # After an escape the protocol is tried again this long later while the road works last.
    retry_after_s: float = Field(5.0, gt=0)
    roadworks_cause_code: int = 3
    # A vehicle still in the closed lane stops this far before the works' DENM event position.
    stop_before_works_m: float = Field(10.0, ge=0)
    # Our own length: a car in the target lane whose front is less than side_margin_m behind our rear bumper
    # is alongside us, whatever STOM says, and a merger falls in behind it first, drop_back_mps slower than it.
    ego_length_m: float = Field(TYPICAL_CAR_LENGTH_M, gt=0)
    side_margin_m: float = Field(1.0, ge=0)
    drop_back_mps: float = Field(2.0, gt=0)


class IntersectionConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Intersection reference point in the local ENU frame.
    reference_x_m: float = 0.0
    reference_y_m: float = 0.0
    competition_zone_radius_m: float = Field(100.0, gt=0)
    # Absolute stack time at which to enter the competition zone; 0 = as soon as possible.
    arrival_time_s: float = 0.0
    arrival_speed_mps: float = Field(30.0 * KPH, gt=0)
    speed_limit_mps: float = Field(50.0 * KPH, gt=0)
    # (unconfirmed) GCDC safety circle around each vehicle.
    safety_circle_m: float = Field(7.5, gt=0)
    # A priority vehicle this close to the reference point, coming closer, has to be given way to.
    conflict_radius_m: float = Field(60.0, gt=0)
    # Half size of the intersection box: the stop line is this far before the reference point and the
    # box is cleared this far after it.
    box_half_size_m: float = Field(15.0, gt=0)
    organiser_station_ids: list[int] = Field(default_factory=list)
    intention: Intention = Intention.STRAIGHT
    approach_timeout_s: float = Field(120.0, gt=0)
    give_way_timeout_s: float = Field(30.0, gt=0)
    crossing_timeout_s: float = Field(30.0, gt=0)
    # How long the scene must show the conflict area free before a held vehicle crosses.
    clear_hold_s: float = Field(2.0, gt=0)


class EmergencyConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # ETSI cause code emergencyVehicleApproaching.
    denm_cause_code: int = 95
    # Lanes with this index or higher open the corridor to their left edge, the others to their right.
    left_of_corridor_lane_index: int = 1
    corridor_offset_m: float = Field(0.9, gt=0)
    corridor_speed_mps: float = Field(30.0 * KPH, gt=0)
    corridor_settled_m: float = Field(0.2, gt=0)
    open_timeout_s: float = Field(8.0, gt=0)
    hold_timeout_s: float = Field(60.0, gt=0)
    close_timeout_s: float = Field(8.0, gt=0)
    # The emergency vehicle is past when its rear is this far ahead of our front.
    passed_margin_m: float = Field(10.0, ge=0)
    # Only an emergency vehicle behind us and closer than this asks for a corridor.
    relevance_m: float = Field(500.0, gt=0)
    # Losing the emergency vehicle's messages this long ends the corridor (it is gone or never came).
    lost_after_s: float = Field(3.0, gt=0)


class SignalConfig(BaseModel):
    """Traffic lights: the MAPEM's ingress lanes and signal groups, the SPATEM's phases (services/planner/signals/)."""

    model_config = ConfigDict(extra="forbid")

    # The movement the ego takes at a signalised intersection, whose signal group it obeys.
    intention: Intention = Intention.STRAIGHT
    # Matching the ego to an ingress lane: its centre line this close sideways (when the MAP gives no lane width;
    # else half its width plus match_margin_m), its direction of travel this close to the ego heading.
    lane_half_width_m: float = Field(1.75, gt=0)
    match_margin_m: float = Field(0.5, ge=0)
    heading_tolerance_deg: float = Field(30.0, gt=0, lt=90)
    # Matched to no lane, the ego still stops safely at a signalised lane's stop line ahead within this distance
    # sideways (its own lane missing from the MAP, or the MAP not where the road is), while it is within the lane's
    # length of it.
    mismatch_lateral_m: float = Field(10.0, gt=0)
    # Do not block the box: on green the ego stays at the line while the vehicle ahead, no faster than
    # queue_speed_mps, leaves less than box_clear_m past the stop line (the box and our own length).
    queue_speed_mps: float = Field(1.0, ge=0)
    box_clear_m: float = Field(25.0, gt=0)
    # An ingress lane is followed this far past its stop line (the intersection box) before the match is lost.
    box_length_m: float = Field(40.0, gt=0)
    # Deceleration a stop at the line may take: ITE's amber-interval practice (Institute of Transportation
    # Engineers, "Guidelines for Determining Traffic Signal Change and Clearance Intervals", 2020) designs amber for
    # 10 ft/s2 = 3.05 m/s2; a vehicle that would need more on amber is in the dilemma zone and proceeds.
    comfort_decel_mps2: float = Field(3.0, gt=0)
    # From a decision to braking (planner period, control, actuator lag), in the stopping distance v t + v2/(2 a).
    reaction_time_s: float = Field(0.5, ge=0)
    # The rear axle (the ego position) to the front bumper: stop line distances are the front bumper's.
    rear_axle_to_front_m: float = Field(3.8, ge=0)
    # GLOSA arrives this long after a green starts (the red-amber and the queue's start), never slower than this.
    glosa_margin_s: float = Field(1.0, ge=0)
    glosa_min_speed_mps: float = Field(20.0 * KPH, gt=0)
    # No SPATEM for the ego's signal group this long is stale SPaT: a safe stop at the line. A roadside unit that
    # sends slower is judged at its own pace (the median of its last gaps): stale after spat_stale_periods of them,
    # so that one lost SPATEM is not, and never later than spat_stale_max_s, so that a slow RSU's silence is not
    # trusted for long. At 10 Hz the 1 s decides; at 0.5 Hz, 3 gaps (6 s) capped at 5 s.
    spat_stale_s: float = Field(1.0, gt=0)
    spat_stale_periods: float = Field(3.0, ge=1)
    spat_stale_max_s: float = Field(5.0, gt=0)
    # SPaT that contradicted itself (minEndTime after maxEndTime, an end time jumping back, a phase ending before
    # its minEndTime) is not trusted for this long after the last contradiction; end times may wander this much.
    contradiction_hold_s: float = Field(5.0, gt=0)
    timing_tolerance_s: float = Field(0.5, ge=0)

    @model_validator(mode="after")
    def _stale_limits_in_order(self) -> SignalConfig:
        if self.spat_stale_max_s < self.spat_stale_s:
            raise ValueError(f"spat_stale_max_s {self.spat_stale_max_s:g} is below spat_stale_s {self.spat_stale_s:g}")
        return self

    def stale_after_s(self, period_s: float | None) -> float:
        """How long after its last SPATEM a group's SPaT is stale, for an intersection sending every period_s
        (None: not known yet)."""
        paced_s = 0.0 if period_s is None else self.spat_stale_periods * period_s
        return min(max(self.spat_stale_s, paced_s), self.spat_stale_max_s)


class PlannerLogicConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    history_length: int = Field(32, gt=0)
    # How often the Mermaid graph is attached to PlannerState (it is large and static).
    graph_period_s: float = Field(5.0, gt=0)
    # A vehicle not heard for 400 ms was shown as lost at GCDC.
    partner_silent_s: float = Field(0.4, gt=0)
    cruise_speed_mps: float = Field(25.0, gt=0)
    # (eq. 4) Heudiasyc spacing r + h v, standstill r.
    standstill_m: float = Field(SPACING.standstill_m, ge=0)
    platoon: PlatoonConfig = Field(default_factory=PlatoonConfig)
    merge: MergeConfig = Field(default_factory=MergeConfig)
    intersection: IntersectionConfig = Field(default_factory=IntersectionConfig)
    emergency: EmergencyConfig = Field(default_factory=EmergencyConfig)
    signals: SignalConfig = Field(default_factory=SignalConfig)


class PlannerConfig(ServiceConfig):
    rate_hz: float = Field(10.0, gt=0)
    # Our ITS station id (as the v2x service sends it).
    station_id: int = Field(1, gt=0)
    # A coopdrive.v1.Scenario name, e.g. SCENARIO_FOLLOW, SCENARIO_MERGE.
    scenario: str = "SCENARIO_FOLLOW"
    # 1 platoon A, 2 platoon B; 0 when not in a platoon.
    platoon_id: int = 0
    partner_station_id: int = 0
    # GLOSA (green light optimal speed advisory): slow down on a signalised approach to arrive on green rather than
    # stop; false: only stop on amber and red and go on green.
    glosa: bool = True
    # The service clock plus this instant is UTC, which SPaT times count in. None: the clock already is unix time
    # (the wall clock); in simulation the UTC instant of sim time 0, as the v2x service's clock_epoch_utc.
    clock_epoch_utc: AwareDatetime | None = None
    logic: PlannerLogicConfig = Field(default_factory=PlannerLogicConfig)

    def scenario_value(self) -> int:
        try:
            return planner_pb2.Scenario.Value(self.scenario)
        except ValueError:
            names = ", ".join(planner_pb2.Scenario.keys())
            raise ValueError(f"scenario {self.scenario!r} is not one of {names}") from None

    @property
    def clock_epoch_unix_s(self) -> float:
        return 0.0 if self.clock_epoch_utc is None else self.clock_epoch_utc.timestamp()
