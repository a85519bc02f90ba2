"""Plain data passed into and out of the longitudinal laws."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

from coopdrive.v1 import control_pb2, planner_pb2

LongitudinalMode = control_pb2.LongitudinalMode

# Below this a vehicle stands: measured speeds of a standing car jitter around zero by a few cm/s.
STANDSTILL_SPEED_MPS = 0.1
TargetRole = planner_pb2.TargetRole


class CaccLaw(enum.Enum):
    """Which cooperative law runs when V2V is fresh."""

    OURS = "ours"
    PLOEG = "ploeg"


class AccLaw(enum.Enum):
    """Which radar-only law runs when V2V is lost and dCACC has no estimate yet."""

    OURS = "ours"
    RAJAMANI = "rajamani"


class SpeedLaw(enum.Enum):
    PI = "pi"
    DRIVERTIVE = "drivertive"


@dataclass(frozen=True)
class Target:
    """One vehicle the planner asked us to keep a gap to (planner TargetVehicle joined with the scene).

    accel_mps2 is the predecessor's acceleration received over V2V (CAM / iCLCM), None when absent.
    v2v_age_s is the age of that V2V data, None when the target has no V2V at all.
    intended_accel_mps2 is the acceleration its controller requests (iCLCM), None when not fresh.
    in_path says it drives where we drive: in our lane or our corridor. A virtual target of the merge drives in
    the other lane; the follow laws keep a gap to it, but nothing we can hit is there until it is in our path.
    """

    object_id: int
    gap_m: float
    speed_mps: float
    accel_mps2: float | None = None
    v2v_age_s: float | None = None
    role: int = TargetRole.TARGET_ROLE_PREDECESSOR
    extra_gap_m: float = 0.0
    # A line to stop at (give way, road works), not a vehicle: gap_m is the distance to the stopping point.
    stop_line: bool = False
    intended_accel_mps2: float | None = None
    in_path: bool = True

    def invalid_reason(self) -> str | None:
        if not math.isfinite(self.gap_m):
            return f"target {self.object_id}: gap_m is not finite"
        if not math.isfinite(self.speed_mps):
            return f"target {self.object_id}: speed_mps is not finite"
        if self.accel_mps2 is not None and not math.isfinite(self.accel_mps2):
            return f"target {self.object_id}: accel_mps2 is not finite"
        if self.intended_accel_mps2 is not None and not math.isfinite(self.intended_accel_mps2):
            return f"target {self.object_id}: intended_accel_mps2 is not finite"
        if self.v2v_age_s is not None and not (self.v2v_age_s >= 0):
            return f"target {self.object_id}: v2v_age_s must be >= 0"
        return None


@dataclass(frozen=True)
class Spacing:
    """Spacing policy d = standstill_m + time_gap_s * v (Heudiasyc eq. 4); same fields as planner SpacingPolicy."""

    standstill_m: float
    time_gap_s: float


@dataclass(frozen=True)
class FollowInput:
    """What a following law sees of one target at one instant."""

    gap_m: float
    ego_speed_mps: float
    ego_accel_mps2: float
    pred_speed_mps: float
    pred_accel_mps2: float
    standstill_m: float
    time_gap_s: float
    # The acceleration the predecessor's controller requests (iCLCM), None when not fresh.
    pred_intended_accel_mps2: float | None = None

    @property
    def pred_feedforward_accel_mps2(self) -> float:
        """What the cooperative laws feed forward: the predecessor's request when fresh, else its measurement."""
        return self.pred_accel_mps2 if self.pred_intended_accel_mps2 is None else self.pred_intended_accel_mps2

    @property
    def desired_gap_m(self) -> float:
        return self.standstill_m + self.time_gap_s * self.ego_speed_mps  # Heudiasyc eq. 4

    @property
    def spacing_error_m(self) -> float:
        return self.gap_m - self.desired_gap_m

    @property
    def spacing_error_rate_mps(self) -> float:
        # d/dt of the spacing error with constant r and h (Ploeg's v_p - v - h a).
        return self.pred_speed_mps - self.ego_speed_mps - self.time_gap_s * self.ego_accel_mps2


@dataclass
class LongitudinalCommand:
    accel_request_mps2: float
    mode: int
    emergency_brake: bool = False
    target_object_id: int = 0
    gap_m: float = 0.0
    desired_gap_m: float = 0.0
    time_gap_s: float = 0.0
    cruise_speed_mps: float = 0.0
    # iCLCM responseTimeConstant / responseTimeDelay of this vehicle.
    response_time_constant_s: float = 0.0
    response_time_delay_s: float = 0.0
    # Each law's unconstrained output this step, keyed "cruise" or "<mode>:<object_id>", for logging.
    law_outputs_mps2: dict[str, float] = field(default_factory=dict)

    def fill(self, msg: control_pb2.ControlCommand) -> control_pb2.ControlCommand:
        """Copy the longitudinal fields into a ControlCommand (the lateral ones are left alone)."""
        msg.accel_request_mps2 = self.accel_request_mps2
        msg.longitudinal_mode = self.mode
        msg.emergency_brake = self.emergency_brake
        msg.target_object_id = self.target_object_id
        msg.gap_m = self.gap_m
        msg.desired_gap_m = self.desired_gap_m
        msg.time_gap_s = self.time_gap_s
        msg.cruise_speed_mps = self.cruise_speed_mps
        msg.response_time_constant_s = self.response_time_constant_s
        msg.response_time_delay_s = self.response_time_delay_s
        return msg
