"""Plain data for the lateral laws. Frenet frame of the reference lane: offsets positive left, angles CCW."""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from coopdrive.v1 import control_pb2

LateralMode = control_pb2.LateralMode


class LateralLaw(enum.Enum):
    HEUDIASYC_PD = "heudiasyc_pd"
    STANLEY = "stanley"
    PURE_PURSUIT = "pure_pursuit"


@dataclass(frozen=True)
class PathState:
    """Ego (rear axle) relative to the reference lane centre, plus the reference offset to track.

    lateral_offset_m: ego offset y from the lane centre, positive left (LanePosition.lateral_offset_m).
    heading_error_rad: ego heading minus lane heading, theta.
    reference_*: y_d and its derivatives (lane change profile), offsets from the same centre line.
    """

    speed_mps: float
    lateral_offset_m: float
    heading_error_rad: float
    curvature_1pm: float = 0.0
    reference_offset_m: float = 0.0
    reference_rate_mps: float = 0.0
    reference_accel_mps2: float = 0.0
    # y_d at a time this many seconds ahead (the lane change profile), for look-ahead laws.
    reference_preview: Callable[[float], float] | None = None

    @property
    def lateral_error_m(self) -> float:
        """e_l = y_d - y (Heudiasyc eq. 10 sign: positive means steer left)."""
        return self.reference_offset_m - self.lateral_offset_m


@dataclass
class LateralCommand:
    steering_angle_rad: float
    curvature_1pm: float
    mode: int
    lateral_error_m: float
    heading_error_rad: float
    reference_offset_m: float
    lane_change_active: bool = False

    def fill(self, msg: control_pb2.ControlCommand) -> control_pb2.ControlCommand:
        msg.steering_angle_request_rad = self.steering_angle_rad
        msg.curvature_request_1pm = self.curvature_1pm
        msg.lateral_mode = self.mode
        msg.lateral_error_m = self.lateral_error_m
        msg.heading_error_rad = self.heading_error_rad
        return msg


class SteeringLaw(Protocol):
    """The contract of the interchangeable lateral laws (Heudiasyc's PD, Stanley, pure pursuit)."""

    def steering_rad(self, p: PathState) -> float:
        """The road-wheel angle (rad, positive left) that brings the vehicle onto the reference of p."""
