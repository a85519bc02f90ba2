"""When to send a CAM or an iCLCM and what it says, from the latest ego state, behaviour request and command.

Pure logic: generators are fed messages and asked, with the service time and its TimestampIts, whether a
message is due; they return the content to send or None.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.geodesy import GeodeticOrigin
from coopdrive.geodesy import LocalTangentPlane
from coopdrive.v2x.timebase import generation_delta_time_ms
from coopdrive.v2x.units import EARTH_RADIUS_M
from coopdrive.v1 import control_pb2, ego_pb2, its_pb2, planner_pb2

GCDC_RATE_HZ = 25.0
TIME_EPSILON_S = 1e-6
GCDC_PERIOD_S = 1.0 / GCDC_RATE_HZ
# EN 302 637-2 section 6.1.3: CAM generation interval bounds and trigger thresholds.
T_GEN_CAM_MIN_S = 0.1
T_GEN_CAM_MAX_S = 1.0
N_GEN_CAM = 3
HEADING_TRIGGER_RAD = math.radians(4.0)
POSITION_TRIGGER_M = 4.0
SPEED_TRIGGER_MPS = 0.5
LOW_FREQUENCY_PERIOD_S = 0.5
# An ego state older than this is stale, not late: its position is not carried forward (a stalled estimate
# carried far would make the receivers see the car jump when fresh ones resume).
MAX_POSITION_AGE_S = 0.2
# 95 % confidence ellipse axis of a 2-D Gaussian from its standard deviation: sqrt(chi2(2, 0.95)).
CONFIDENCE_95_PER_STD = math.sqrt(5.991)
MIN_SPEED_FOR_CURVATURE_MPS = 0.5

CONTROLLER_OF_MODE = {
    control_pb2.LONGITUDINAL_MODE_UNSPECIFIED: its_pb2.CONTROLLER_TYPE_MANUAL,
    control_pb2.LONGITUDINAL_MODE_CRUISE: its_pb2.CONTROLLER_TYPE_CC,
    control_pb2.LONGITUDINAL_MODE_ACC: its_pb2.CONTROLLER_TYPE_ACC,
    control_pb2.LONGITUDINAL_MODE_CACC: its_pb2.CONTROLLER_TYPE_CACC,
    # Radar-only following, braking and holding still are automated control without the V2V feed forward.
    control_pb2.LONGITUDINAL_MODE_DCACC: its_pb2.CONTROLLER_TYPE_ACC,
    control_pb2.LONGITUDINAL_MODE_EMERGENCY_BRAKE: its_pb2.CONTROLLER_TYPE_ACC,
    control_pb2.LONGITUDINAL_MODE_STANDSTILL: its_pb2.CONTROLLER_TYPE_ACC,
}


class CamMode(enum.Enum):
    # GCDC 2016: every CAM at 25 Hz.
    GCDC = "gcdc"
    # EN 302 637-2 generation rules: 1-10 Hz, triggered by the vehicle dynamics.
    ETSI = "etsi"


class VehicleDimensions(BaseModel):
    """The sender's size as CAMs and iCLCMs carry it (also a section of the v2x service's configuration)."""

    model_config = ConfigDict(extra="forbid")

    length_m: float = Field(4.5, gt=0.0)
    width_m: float = Field(1.8, gt=0.0)
    # Rear axle to the front bumper: the iCLCM rearAxleLocation.
    rear_axle_location_m: float = Field(3.5, ge=0.0)


class CamTrigger(enum.Enum):
    """Why a CAM was generated (for counters and tests)."""

    GCDC_PERIOD = "gcdc_period"
    FIRST = "first"
    HEADING = "heading"
    POSITION = "position"
    SPEED = "speed"
    T_GEN_CAM = "t_gen_cam"


@dataclass(frozen=True)
class _Sent:
    time_s: float
    x_m: float
    y_m: float
    heading_rad: float
    speed_mps: float


def wrap_angle_rad(angle_rad: float) -> float:
    return (angle_rad + math.pi) % (2 * math.pi) - math.pi


class CamGenerator:
    """CAMs from the latest EgoState, at 25 Hz (GCDC) or by the EN 302 637-2 rules."""

    def __init__(self, mode: CamMode, station_id: int, station_type: int, protocol_version: int,
                 origin: GeodeticOrigin, vehicle: VehicleDimensions):
        self.mode = mode
        self.station_id = station_id
        self.station_type = station_type
        self.protocol_version = protocol_version
        self.origin = origin
        self.plane = LocalTangentPlane(origin.lat_deg, origin.lon_deg, origin.alt_m)
        self.vehicle = vehicle
        self.ego: ego_pb2.EgoState | None = None
        self.last_trigger: CamTrigger | None = None
        self._last: _Sent | None = None
        self._last_low_frequency_s: float | None = None
        self._t_gen_cam_s = T_GEN_CAM_MAX_S
        self._repeats_left = 0

    def on_ego_state(self, ego: ego_pb2.EgoState) -> None:
        self.ego = ego

    def generate(self, now_s: float, tai_ms: int) -> its_pb2.CamContent | None:
        # A CAM tells others where we are: with no position estimate yet there is nothing true to say.
        if self.ego is None or self.ego.mode == ego_pb2.LOCALISATION_MODE_LOST:
            return None
        trigger = self._trigger(now_s)
        if trigger is None:
            return None
        self.last_trigger = trigger
        ego = self.ego
        self._last = _Sent(now_s, ego.x_m, ego.y_m, ego.heading_rad, ego.speed_mps)
        content = self._content(ego, tai_ms, self._position_age_s(ego, now_s))
        if self._last_low_frequency_s is None or now_s - self._last_low_frequency_s >= LOW_FREQUENCY_PERIOD_S - TIME_EPSILON_S:
            self._last_low_frequency_s = now_s
            content.low_frequency.SetInParent()
        return content

    @staticmethod
    def _position_age_s(ego: ego_pb2.EgoState, now_s: float) -> float:
        """How old the latest position estimate is when the CAM goes out. generationDeltaTime is the time of
        the reference position (EN 302 637-2) and must grow from CAM to CAM, so the position is carried
        forward to now rather than the time set back: a receiver then does not place a car at 80 km/h a metre
        behind itself."""
        age_s = now_s - ego.header.sample_time_s
        return age_s if 0.0 < age_s <= MAX_POSITION_AGE_S else 0.0

    def _trigger(self, now_s: float) -> CamTrigger | None:
        last = self._last
        if last is None:
            return CamTrigger.FIRST
        elapsed_s = now_s - last.time_s
        if self.mode is CamMode.GCDC:
            return CamTrigger.GCDC_PERIOD if elapsed_s >= GCDC_PERIOD_S - TIME_EPSILON_S else None
        if elapsed_s < T_GEN_CAM_MIN_S - TIME_EPSILON_S:
            return None
        dynamics = self._dynamics_trigger(last)
        if dynamics is not None:
            # Condition 1: keep sending at the interval the dynamics asked for, N_GEN_CAM times (section 6.1.3).
            self._t_gen_cam_s = min(max(elapsed_s, T_GEN_CAM_MIN_S), T_GEN_CAM_MAX_S)
            self._repeats_left = N_GEN_CAM
            return dynamics
        if elapsed_s >= self._t_gen_cam_s - TIME_EPSILON_S:
            self._repeats_left -= 1
            if self._repeats_left <= 0:
                self._t_gen_cam_s = T_GEN_CAM_MAX_S
            return CamTrigger.T_GEN_CAM
        return None

    def _dynamics_trigger(self, last: _Sent) -> CamTrigger | None:
        ego = self.ego
        if abs(wrap_angle_rad(ego.heading_rad - last.heading_rad)) > HEADING_TRIGGER_RAD:
            return CamTrigger.HEADING
        if math.hypot(ego.x_m - last.x_m, ego.y_m - last.y_m) > POSITION_TRIGGER_M:
            return CamTrigger.POSITION
        if abs(ego.speed_mps - last.speed_mps) > SPEED_TRIGGER_MPS:
            return CamTrigger.SPEED
        return None

    def wgs84(self, ego: ego_pb2.EgoState) -> tuple[float, float, float]:
        """(lat, lon, alt): the EgoState's own latitude/longitude when set, else its ENU position."""
        o = self.origin
        if ego.latitude_deg or ego.longitude_deg:
            return ego.latitude_deg, ego.longitude_deg, o.alt_m
        return self.plane.to_geodetic(ego.x_m, ego.y_m)

    def reference_point_wgs84(self, ego: ego_pb2.EgoState, age_s: float = 0.0) -> tuple[float, float, float]:
        """(lat, lon, alt) of the CAM reference point, the centre of the vehicle's front (EN 302 637-2):
        the EgoState is at the rear axle, rear_axle_location_m behind the front bumper, and age_s old."""
        latitude_deg, longitude_deg, altitude_m = self.wgs84(ego)
        ahead_m = self.vehicle.rear_axle_location_m + ego.speed_mps * age_s
        north_m, east_m = ahead_m * math.sin(ego.heading_rad), ahead_m * math.cos(ego.heading_rad)
        latitude_deg += math.degrees(north_m / EARTH_RADIUS_M)
        longitude_deg += math.degrees(east_m / (EARTH_RADIUS_M * math.cos(math.radians(latitude_deg))))
        return latitude_deg, longitude_deg, altitude_m

    def _content(self, ego: ego_pb2.EgoState, tai_ms: int, age_s: float = 0.0) -> its_pb2.CamContent:
        content = its_pb2.CamContent(protocol_version=self.protocol_version, station_id=self.station_id,
                                     generation_delta_time_ms=generation_delta_time_ms(tai_ms),
                                     station_type=self.station_type)
        position = content.reference_position
        position.latitude_deg, position.longitude_deg, position.altitude_m = self.reference_point_wgs84(ego, age_s)
        if ego.position_std_m > 0:
            position.semi_major_confidence_m = position.semi_minor_confidence_m = \
                CONFIDENCE_95_PER_STD * ego.position_std_m
        hf = content.high_frequency
        hf.heading_rad = ego.heading_rad
        hf.speed_mps = abs(ego.speed_mps)
        hf.drive_direction = its_pb2.DRIVE_DIRECTION_BACKWARD if ego.speed_mps < 0 else its_pb2.DRIVE_DIRECTION_FORWARD
        hf.vehicle_length_m = self.vehicle.length_m
        hf.vehicle_length_confidence = its_pb2.VEHICLE_LENGTH_CONFIDENCE_NO_TRAILER_PRESENT
        hf.vehicle_width_m = self.vehicle.width_m
        hf.longitudinal_acceleration_mps2 = ego.accel_mps2
        hf.yaw_rate_radps = ego.yaw_rate_radps
        if abs(ego.speed_mps) >= MIN_SPEED_FOR_CURVATURE_MPS:
            hf.curvature_per_m = ego.yaw_rate_radps / ego.speed_mps
            hf.curvature_calculation_mode = its_pb2.CURVATURE_CALCULATION_MODE_YAW_RATE_USED
        return content


class IclcmGenerator:
    """iCLCMs at a fixed rate: the planner's IclcmIntent plus control's high-frequency fields."""

    def __init__(self, station_id: int, vehicle: VehicleDimensions, rate_hz: float = GCDC_RATE_HZ):
        self.station_id = station_id
        self.vehicle = vehicle
        self.period_s = 1.0 / rate_hz
        self.behaviour: planner_pb2.BehaviourRequest | None = None
        self.command: control_pb2.ControlCommand | None = None
        self._last_s: float | None = None
        self._last_low_frequency_s: float | None = None

    def on_behaviour(self, behaviour: planner_pb2.BehaviourRequest) -> None:
        self.behaviour = behaviour

    def on_command(self, command: control_pb2.ControlCommand) -> None:
        self.command = command

    def generate(self, now_s: float, tai_ms: int) -> its_pb2.IclcmContent | None:
        if self.behaviour is None and self.command is None:
            return None
        if self._last_s is not None and now_s - self._last_s < self.period_s - TIME_EPSILON_S:
            return None
        self._last_s = now_s
        content = its_pb2.IclcmContent(protocol_version=1, station_id=self.station_id,
                                       generation_delta_time_ms=generation_delta_time_ms(tai_ms),
                                       rear_axle_location_m=self.vehicle.rear_axle_location_m)
        if self.command is not None:
            self._fill_control(content, self.command)
        if self.behaviour is not None:
            self._fill_intent(content, self.behaviour)
        if self._last_low_frequency_s is None or now_s - self._last_low_frequency_s >= LOW_FREQUENCY_PERIOD_S - TIME_EPSILON_S:
            self._last_low_frequency_s = now_s
            content.has_low_frequency = True
            content.participants_ready = self.behaviour is not None and self.behaviour.iclcm.participants_ready
        return content

    @staticmethod
    def _fill_control(content: its_pb2.IclcmContent, command: control_pb2.ControlCommand) -> None:
        content.controller_type = CONTROLLER_OF_MODE.get(command.longitudinal_mode, its_pb2.CONTROLLER_TYPE_MANUAL)
        content.target_longitudinal_acceleration_mps2 = command.accel_request_mps2
        if command.time_gap_s > 0:
            content.time_headway_s = command.time_gap_s
        if command.cruise_speed_mps > 0:
            content.cruise_speed_mps = command.cruise_speed_mps
        if command.response_time_constant_s > 0:
            content.response_time_constant_s = command.response_time_constant_s
        if command.response_time_delay_s > 0:
            content.response_time_delay_s = command.response_time_delay_s
        if command.gap_m > 0:
            content.mio_range_m = command.gap_m

    @staticmethod
    def _fill_intent(content: its_pb2.IclcmContent, behaviour: planner_pb2.BehaviourRequest) -> None:
        intent = behaviour.iclcm
        for target in behaviour.targets:
            if target.role == planner_pb2.TARGET_ROLE_PREDECESSOR:
                content.mio_id = target.station_id
                break
        content.forward_id, content.backward_id = intent.forward_id, intent.backward_id
        content.acknowledge_flag = intent.acknowledge
        content.merge_request, content.merge_safe_to_merge = intent.merge_request, intent.safe_to_merge
        content.merge_flag, content.merge_flag_tail = intent.merge_flag, intent.merge_flag_tail
        content.merge_flag_head = intent.merge_flag_head
        content.platoon_id = intent.platoon_id
        content.distance_travelled_cz_m = intent.distance_travelled_cz_m
        content.intention = intent.intention
        content.counter_intersection = intent.counter_intersection
