"""Faults a scenario injects at given times, one model per kind, told apart by `type`."""
from __future__ import annotations

import enum
import math
from typing import Annotated, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, model_validator

from coopdrive.services.sim.sensor_config import FixModeName


class SensorName(enum.Enum):
    GNSS = "gnss"
    CAN_STATE = "can_state"
    IMU = "imu"
    RADAR = "radar"
    LIDAR = "lidar"
    CAMERA = "camera"
    SONAR = "sonar"


class _Fault(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    start_s: float = Field(ge=0)
    # Open-ended when left out.
    end_s: float = math.inf

    @model_validator(mode="after")
    def _ends_after_start(self) -> _Fault:
        if self.end_s <= self.start_s:
            raise ValueError(f"end_s {self.end_s} must be after start_s {self.start_s}")
        return self

    def active(self, now_s: float) -> bool:
        return self.start_s <= now_s < self.end_s

    def concerns(self, vehicle_id: str) -> bool:
        """Whether the fault acts on the vehicle: the one it names, or every vehicle when it names none."""
        return getattr(self, "vehicle_id", None) in (vehicle_id, None)


class GnssOutage(_Fault):
    type: Literal["gnss_outage"]
    vehicle_id: str


class GnssJump(_Fault):
    """Multipath: the receiver's fixes are off by this offset, still in their configured fix mode."""

    type: Literal["gnss_jump"]
    vehicle_id: str
    east_m: float = 5.0
    north_m: float = 0.0
    # The offset grows linearly to its full size over this time (0: a step), as a multipath or atmospheric
    # error builds up slowly enough for a filter's innovation gate to accept every fix.
    ramp_s: float = Field(default=0.0, ge=0)

    def offset_at(self, now_s: float) -> tuple[float, float]:
        """(east, north) offset in m at now_s while active."""
        share = 1.0 if self.ramp_s == 0.0 else min(1.0, max(0.0, (now_s - self.start_s) / self.ramp_s))
        return share * self.east_m, share * self.north_m


class GnssMultipath(_Fault):
    """Multipath beside a wall or a truck: the fixes jump by about jump_m in a new random direction every hop_s,
    the receiver still claiming its mode and accuracy (unlike gnss_jump, one fixed offset)."""

    type: Literal["gnss_multipath"]
    vehicle_id: str
    jump_m: float = Field(default=3.0, gt=0)
    hop_s: float = Field(default=1.0, gt=0)


class RadarClutter(_Fault):
    """The vehicle's radar reports this many false tracks per scan (stationary reflectors: a gantry, guardrail
    posts, a tunnel entrance), each for one scan, anywhere in its field of view."""

    type: Literal["radar_clutter"]
    vehicle_id: str
    false_alarms_per_scan: float = Field(default=5.0, ge=0)


class LidarClutter(_Fault):
    """The vehicle's LiDAR looks through spray or heavy rain: this fraction of its beams echoes off the droplets
    somewhere short of what it would have hit (the world's `clutter_probability` is the dry-road rate)."""

    type: Literal["lidar_clutter"]
    vehicle_id: str
    clutter_probability: float = Field(default=0.05, gt=0, le=1)


class FixDowngrade(_Fault):
    type: Literal["fix_downgrade"]
    vehicle_id: str
    fix_mode: FixModeName


class V2vLoss(_Fault):
    """Packets to and from vehicle_id (every vehicle when left out) are lost with this probability."""

    type: Literal["v2v_loss"]
    vehicle_id: str | None = None
    loss_probability: float = Field(default=1.0, ge=0, le=1)


class V2vCorruption(_Fault):
    type: Literal["v2v_corruption"]
    corruption_probability: float = Field(default=0.1, ge=0, le=1)


class SensorDropout(_Fault):
    type: Literal["sensor_dropout"]
    vehicle_id: str
    sensor: SensorName


class CanErrorBurst(_Fault):
    """The vehicle bus carries error frames at this rate and loses the state frames meanwhile."""

    type: Literal["can_error_burst"]
    vehicle_id: str
    error_frames_per_s: float = Field(default=500.0, gt=0)


class PartnerSilent(_Fault):
    """The vehicle stops transmitting on the radio (it still drives)."""

    type: Literal["partner_silent"]
    vehicle_id: str


class IclcmFlag(enum.Enum):
    """The iCLCM fields that carry a step of the merge or intersection protocol (names as in its.proto's
    IclcmContent)."""

    FORWARD_ID = "forward_id"
    BACKWARD_ID = "backward_id"
    ACKNOWLEDGE_FLAG = "acknowledge_flag"
    MERGE_REQUEST = "merge_request"
    MERGE_SAFE_TO_MERGE = "merge_safe_to_merge"
    MERGE_FLAG = "merge_flag"
    MERGE_FLAG_HEAD = "merge_flag_head"
    MERGE_FLAG_TAIL = "merge_flag_tail"
    # Intersection: the count of vehicles that crossed, raised by each vehicle leaving the box.
    COUNTER_INTERSECTION = "counter_intersection"


class IclcmDrop(_Fault):
    """The radio loses the first `count` iCLCMs vehicle_id sends with `flag` set (a protocol step's message);
    with `duration_s`, every such iCLCM for that long from the first one, so that the 25 Hz repetition cannot
    make the step good 40 ms later (a step lost past the partner timeout)."""

    type: Literal["iclcm_drop"]
    vehicle_id: str
    flag: IclcmFlag
    count: int | None = Field(default=None, ge=1)
    duration_s: float | None = Field(default=None, gt=0)

    @model_validator(mode="after")
    def _count_or_duration(self) -> IclcmDrop:
        if self.count is not None and self.duration_s is not None:
            raise ValueError("give count or duration_s, not both")
        return self


class GhostVehicle(_Fault):
    """CAMs from a station that does not exist: they claim a car `gap_m` ahead of vehicle_id's front bumper in
    its lane (offset `lateral_m` to the left), driving at its speed. A spoofer, or a replayed CAM stream."""

    type: Literal["ghost_vehicle"]
    vehicle_id: str
    station_id: int = Field(default=999_001, ge=0, lt=2 ** 32)
    gap_m: float = 20.0
    lateral_m: float = 0.0
    rate_hz: float = Field(default=10.0, gt=0)


class PositionOffset(_Fault):
    """A scripted vehicle's CAMs place it east_m/north_m off where it is (a biased receiver or a liar)."""

    type: Literal["position_offset"]
    vehicle_id: str
    east_m: float = 5.0
    north_m: float = 0.0


class ServiceCrash(_Fault):
    """The named stack service of the vehicle is killed at start_s and restarted at end_s (if given)."""

    type: Literal["service_crash"]
    vehicle_id: str
    service: str = Field(min_length=1)


class TicketExpired(_Fault):
    """The vehicle's authorisation tickets (all of them) expire at start_s: from then on every verifying station
    refuses its packets (certificate_expired). Needs a secured run (`coopdrive run --security MODE`); end_s is
    ignored, an expired ticket stays expired."""

    type: Literal["ticket_expired"]
    vehicle_id: str


class SpatLoss(_Fault):
    """The roadside unit of a signalised intersection sends no SPATEM (its MAPEM goes on): a stale signal state."""

    type: Literal["spat_loss"]
    unit_id: str


class SpatTimeJump(_Fault):
    """The unit's SPATEMs state every phase end jump_s later than the controller will end it (negative: earlier):
    timing that jumps, as a controller's clock stepping or a plan changed under the announcement would."""

    type: Literal["spat_time_jump"]
    unit_id: str
    jump_s: float = 10.0


class MapLaneOffset(_Fault):
    """The unit's MAPEM places its lanes east_m/north_m off the road (its reference point moved, every node with
    it): a map whose lanes do not match the vehicles' paths (3.5 m north puts the eastbound lanes on the
    westbound ones)."""

    type: Literal["map_lane_offset"]
    unit_id: str
    east_m: float = 0.0
    north_m: float = 3.5


# Faults of a signalised intersection's roadside unit (signal_rsu.py carries them out).
SIGNAL_FAULTS = (SpatLoss, SpatTimeJump, MapLaneOffset)

Fault = Annotated[Union[GnssOutage, GnssJump, GnssMultipath, RadarClutter, LidarClutter, FixDowngrade, V2vLoss,
                        V2vCorruption, SensorDropout, CanErrorBurst, PartnerSilent, IclcmDrop, GhostVehicle,
                        PositionOffset, ServiceCrash, TicketExpired, SpatLoss, SpatTimeJump, MapLaneOffset],
                 Field(discriminator="type")]
