"""Scripted road users: vehicles following a speed profile and lane changes, and an emergency vehicle.

They drive themselves (no stack inside) and say what they would broadcast as plain intents; the integrator
turns intents into CAM / DENM / iCLCM messages (and a signalised intersection's roadside unit's into MAPEM / SPATEM).
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Any, Sequence

from coopdrive.services.sim.cam_noise import CamNoise
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim.profiles import VehicleProfile
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.services.sim.signal_controller import SignalAspect
from coopdrive.services.sim.stop_line import StopLine
from coopdrive.services.sim.speed_profiles import ConstantSpeed, LaneChange, SpeedProfile, smoothstep
from coopdrive.v1 import sensors_pb2, sim_pb2

DEFAULT_CAM_RATE_HZ = 25.0  # GCDC sent CAM, DENM and iCLCM at 25 Hz
# Step of the numerical derivative of a speed profile.
_DERIVATIVE_STEP_S = 1e-3
# DENM cause code of an approaching emergency vehicle (ETSI EN 302 637-3).
EMERGENCY_VEHICLE_APPROACHING_CAUSE = 95
# A scripted driver follows its script but is not blind: it keeps a spacing r + h v to whoever blocks its
# path (a vehicle ahead whose footprint overlaps its own across the lane, plus a margin).
KEEP_STANDSTILL_M = 4.0
KEEP_TIME_GAP_S = 1.2
KEEP_SPEED_GAIN_PER_S = 0.5
KEEP_MAX_DECEL_MPS2 = 6.0
KEEP_MAX_ACCEL_MPS2 = 2.0
KEEP_LATERAL_MARGIN_M = 0.3
# At a traffic light it stops with its front bumper this far before the stop line, braking at this deceleration;
# on amber it stops only when it can at this deceleration, else it goes on (the dilemma-zone rule of ITE's
# kinematic amber, whose deceleration is 3.0 m/s2, 10 ft/s2).
STOP_LINE_MARGIN_M = 1.0
SIGNAL_STOP_DECEL_MPS2 = 3.0


def cam_fields_of(t: sim_pb2.VehicleTruth) -> dict[str, Any]:
    """A CAM's fields of a vehicle's truth (what it would send knowing exactly where it is)."""
    return {"x_m": t.x_m, "y_m": t.y_m, "heading_rad": t.heading_rad, "speed_mps": t.speed_mps,
            "accel_mps2": t.accel_mps2, "yaw_rate_radps": t.yaw_rate_radps, "length_m": t.length_m,
            "width_m": t.width_m, "lane": t.lane_index}


class IntentKind(enum.Enum):
    CAM = "cam"
    DENM = "denm"
    ICLCM = "iclcm"
    MAPEM = "mapem"
    SPATEM = "spatem"


@dataclass(frozen=True)
class MessageIntent:
    """What a participant would broadcast now; `fields` hold SI values named like the its.proto fields."""

    kind: IntentKind
    sender_id: str
    station_id: int
    time_s: float
    fields: dict[str, Any] = field(default_factory=dict)


class RateGate:
    """True once per period; missed periods are skipped, not caught up."""

    def __init__(self, rate_hz: float, start_s: float = 0.0) -> None:
        self.period_s = 1.0 / rate_hz
        self._next_s = start_s

    def due(self, now_s: float) -> bool:
        if now_s + 1e-9 < self._next_s:
            return False
        periods = math.floor((now_s + 1e-9 - self._next_s) / self.period_s) + 1
        self._next_s += periods * self.period_s
        return True


class ScriptedVehicle:
    """Drives its speed profile along a lane, moving smoothly across lanes at scheduled times, and slows down
    behind whoever blocks its path rather than driving into them (then catches up with its profile).

    `lanes` are the lanes of its road indexed by lane_index. `ignores_protocol` marks the car that keeps
    its script and never answers the cooperative protocol (it still sends CAMs).
    """

    object_class = sensors_pb2.OBJECT_CLASS_CAR

    def __init__(self, vehicle_id: str, station_id: int, profile: VehicleProfile, lanes: Sequence[LaneGeometry],
                 lane_index: int, station_m: float, speed_profile: SpeedProfile | None = None,
                 lane_changes: Sequence[LaneChange] = (), lateral_offset_m: float = 0.0,
                 ignores_protocol: bool = False, cam_rate_hz: float = DEFAULT_CAM_RATE_HZ,
                 start_s: float = 0.0) -> None:
        self.vehicle_id = vehicle_id
        self.station_id = station_id
        self.profile = profile
        self.lanes = {lane.lane_index: lane for lane in lanes}
        if lane_index not in self.lanes:
            raise ValueError(f"{vehicle_id}: no lane {lane_index} among {sorted(self.lanes)}")
        for change in lane_changes:
            if change.target_lane not in self.lanes:
                raise ValueError(f"{vehicle_id}: lane change to missing lane {change.target_lane}")
        self.speed_profile = speed_profile or ConstantSpeed(speed_mps=0.0)
        self.lane_changes = sorted(lane_changes, key=lambda c: c.start_s)
        self.lateral_offset_m = lateral_offset_m
        self.ignores_protocol = ignores_protocol
        self._cam_gate = RateGate(cam_rate_hz, start_s)
        # The receiver whose solution the CAMs carry (None: the exact truth, as in the ideal world).
        self.cam_noise: CamNoise | None = None
        self.lane_index = lane_index
        self.station_m = station_m
        self.time_s = start_s
        self._speed_mps = self.speed_at(start_s)
        self._accel_mps2 = self.accel_at(start_s)
        self._on_profile = True
        self._active_change: LaneChange | None = None
        self._source_lane = lane_index
        self._last_heading: float | None = None
        self._truth = self._compute_truth(0.0)
        # The signalised intersections' stop lines (scenario_builder sets them): it obeys those on its lane.
        self.stop_lines: Sequence[StopLine] = ()
        # The stop lines it decided to stop at (on amber, it keeps to its decision until green).
        self._stopping_at: set[int] = set()

    def speed_at(self, time_s: float) -> float:
        return self.speed_profile.speed_at(time_s)

    def accel_at(self, time_s: float) -> float:
        return (self.speed_at(time_s + _DERIVATIVE_STEP_S) - self.speed_at(time_s - _DERIVATIVE_STEP_S)) / (
            2.0 * _DERIVATIVE_STEP_S)

    def step(self, now_s: float, others: Sequence[sim_pb2.VehicleTruth] = ()) -> sim_pb2.VehicleTruth:
        """Advance to now_s (trapezoidal station update) and return the new truth."""
        dt_s = now_s - self.time_s
        if dt_s < 0.0:
            raise ValueError(f"{self.vehicle_id}: time went back from {self.time_s} to {now_s}")
        old_speed_mps = self._speed_mps
        self._speed_mps, self._accel_mps2 = self._next_speed(now_s, dt_s, self._leader(others))
        self.station_m += 0.5 * (old_speed_mps + self._speed_mps) * dt_s
        self.time_s = now_s
        self._update_lane_change(now_s)
        self._truth = self._compute_truth(dt_s)
        return self._truth

    def _next_speed(self, now_s: float, dt_s: float, leader: tuple[float, float] | None) -> tuple[float, float]:
        """(speed, accel): the profile's while nothing blocks, else the spacing law, within accel limits."""
        profile_mps = self.speed_at(now_s)
        safe_mps = self._signal_limit_mps(now_s, dt_s)
        if leader is not None:
            gap_m, leader_speed_mps = leader
            spacing_m = KEEP_STANDSTILL_M + KEEP_TIME_GAP_S * self._speed_mps
            safe_mps = min(safe_mps, max(0.0, leader_speed_mps + KEEP_SPEED_GAIN_PER_S * (gap_m - spacing_m)))
        if self._on_profile and profile_mps <= safe_mps:
            return profile_mps, self.accel_at(now_s)
        wanted_mps = min(profile_mps, safe_mps)
        if dt_s <= 0.0:
            return self._speed_mps, self._accel_mps2
        low = self._speed_mps - KEEP_MAX_DECEL_MPS2 * dt_s
        high = self._speed_mps + KEEP_MAX_ACCEL_MPS2 * dt_s
        speed_mps = max(0.0, min(max(wanted_mps, low), high))
        self._on_profile = speed_mps >= profile_mps - 1e-9
        return speed_mps, (speed_mps - self._speed_mps) / dt_s

    def _signal_limit_mps(self, now_s: float, dt_s: float) -> float:
        """The speed from which it still stops at the stop line ahead whose light tells it to: red or red-amber,
        or amber when it can stop at SIGNAL_STOP_DECEL_MPS2 (v^2 <= 2 a d)."""
        limit_mps = math.inf
        for line in self.stop_lines:
            distance_m = line.front_distance_m(self._truth)
            if distance_m is None or distance_m < 0.0:
                continue
            key = id(line)
            room_m = max(distance_m - STOP_LINE_MARGIN_M, 0.0)
            aspect = line.aspect(now_s)
            if aspect is SignalAspect.GREEN:
                self._stopping_at.discard(key)
            elif aspect.must_stop or key in self._stopping_at or \
                    self._speed_mps ** 2 <= 2.0 * SIGNAL_STOP_DECEL_MPS2 * room_m:
                self._stopping_at.add(key)
                limit_mps = min(limit_mps, self._stopping_speed_mps(room_m, dt_s))
        return limit_mps

    def _stopping_speed_mps(self, room_m: float, dt_s: float) -> float:
        """The speed v' after this step from which braking at a stops within room_m: the step's trapezoid
        (v + v') dt / 2 plus v'^2 / 2a fit in it, so the braking stays at a down to standstill."""
        a_dt = SIGNAL_STOP_DECEL_MPS2 * dt_s
        discriminant = a_dt ** 2 - 4.0 * (a_dt * self._speed_mps - 2.0 * SIGNAL_STOP_DECEL_MPS2 * room_m)
        return max(0.0, 0.5 * (-a_dt + math.sqrt(discriminant))) if discriminant > 0.0 else 0.0

    def _leader(self, others: Sequence[sim_pb2.VehicleTruth]) -> tuple[float, float] | None:
        """(bumper gap, speed) of the nearest vehicle ahead in the path, along the current lane."""
        lane = self.lanes[self.lane_index]
        own = self._truth
        front_m = own.length_m - rear_overhang_m(own.length_m)
        best: tuple[float, float] | None = None
        for other in others:
            if other.vehicle_id == self.vehicle_id:
                continue
            station_m, lateral_m, lane_heading, _ = lane.project(other.x_m, other.y_m)
            if math.cos(other.heading_rad - lane_heading) <= 0.0:
                continue
            overlap_m = 0.5 * (own.width_m + other.width_m) + KEEP_LATERAL_MARGIN_M
            if abs(lateral_m - own.lateral_offset_m) >= overlap_m:
                continue
            gap_m = station_m - rear_overhang_m(other.length_m) - (own.station_m + front_m)
            if station_m > own.station_m and (best is None or gap_m < best[0]):
                best = (gap_m, other.speed_mps)
        return best

    def truth(self) -> sim_pb2.VehicleTruth:
        return self._truth

    def _update_lane_change(self, now_s: float) -> None:
        if self._active_change is None and self.lane_changes and now_s >= self.lane_changes[0].start_s:
            self._active_change = self.lane_changes.pop(0)
            self._source_lane = self.lane_index
        change = self._active_change
        if change is not None and now_s >= change.start_s + change.duration_s:
            self.station_m = self.lanes[change.target_lane].project(*self._position()[:2])[0]
            self.lane_index = change.target_lane
            self._active_change = None

    def _position(self) -> tuple[float, float, float]:
        """(x_m, y_m, lane heading) of the rear axle, blending source and target lanes during a change."""
        source = self.lanes[self._source_lane if self._active_change else self.lane_index]
        x_m, y_m, heading = source.pose_at(self.station_m, self.lateral_offset_m)
        change = self._active_change
        if change is None:
            return x_m, y_m, heading
        share = smoothstep((self.time_s - change.start_s) / change.duration_s)
        target = self.lanes[change.target_lane]
        station_t, lateral_t, heading_t, _ = target.project(x_m, y_m)
        return (*target.pose_at(station_t, (1.0 - share) * lateral_t + share * self.lateral_offset_m)[:2], heading_t)

    def _compute_truth(self, dt_s: float) -> sim_pb2.VehicleTruth:
        x_m, y_m, lane_heading = self._position()
        heading = lane_heading
        if self._active_change is not None:
            # Heading follows the lateral motion: atan(lateral speed / speed) over the smooth step.
            change = self._active_change
            share = (self.time_s - change.start_s) / change.duration_s
            eps = 1e-3
            slope = (smoothstep(share + eps) - smoothstep(share - eps)) / (2 * eps) / change.duration_s
            source = self.lanes[self._source_lane]
            target = self.lanes[change.target_lane]
            lateral_span_m = target.project(*source.pose_at(self.station_m, 0.0)[:2])[1]
            speed = max(self._speed_mps, 1e-3)
            heading = lane_heading + math.atan2(-lateral_span_m * slope, speed)
        yaw_rate = 0.0
        if self._last_heading is not None and dt_s > 0.0:
            yaw_rate = math.remainder(heading - self._last_heading, math.tau) / dt_s
        self._last_heading = heading
        current = self.lanes[self.lane_index]
        station_m, lateral_m, _, _ = current.project(x_m, y_m)
        return sim_pb2.VehicleTruth(
            vehicle_id=self.vehicle_id, station_id=self.station_id, x_m=x_m, y_m=y_m, heading_rad=heading,
            speed_mps=self._speed_mps, accel_mps2=self._accel_mps2, yaw_rate_radps=yaw_rate,
            length_m=self.profile.length_m, width_m=self.profile.width_m, lane_index=self.lane_index,
            road_id=getattr(current, "road_id", ""), station_m=station_m, lateral_offset_m=lateral_m, automated=False,
        )

    def cam_fields(self) -> dict[str, Any]:
        return cam_fields_of(self._truth)

    def messages_due(self, now_s: float) -> list[MessageIntent]:
        if not self._cam_gate.due(now_s):
            return []
        fields = self.cam_fields()
        if self.cam_noise is not None:
            fields = self.cam_noise.apply(fields, now_s)
        return [MessageIntent(IntentKind.CAM, self.vehicle_id, self.station_id, now_s, fields)]


class EmergencyVehicle(ScriptedVehicle):
    """A scripted vehicle with its siren on between siren_on_s and siren_off_s: CAMs say so and a DENM
    (emergency vehicle approaching) goes out at the CAM rate; it drives at lateral_offset_m from its lane."""

    object_class = sensors_pb2.OBJECT_CLASS_EMERGENCY_VEHICLE

    def __init__(self, *args: Any, siren_on_s: float = 0.0, siren_off_s: float = math.inf, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.siren_on_s = siren_on_s
        self.siren_off_s = siren_off_s

    def siren_on(self, now_s: float) -> bool:
        return self.siren_on_s <= now_s < self.siren_off_s

    def messages_due(self, now_s: float) -> list[MessageIntent]:
        intents = super().messages_due(now_s)
        if not intents:
            return []
        siren = self.siren_on(now_s)
        intents[0].fields.update(emergency=True, light_bar=siren, siren=siren)
        if siren:
            t = self._truth
            intents.append(MessageIntent(IntentKind.DENM, self.vehicle_id, self.station_id, now_s, {
                "cause_code": EMERGENCY_VEHICLE_APPROACHING_CAUSE, "x_m": t.x_m, "y_m": t.y_m,
                "heading_rad": t.heading_rad, "speed_mps": t.speed_mps, "lane": t.lane_index}))
        return intents
