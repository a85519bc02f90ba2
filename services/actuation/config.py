"""Configuration of the actuation service: pedal and steering maps, overrides, modes, watchdog.

Numbers marked DRIVERTIVE come from Medina et al. 2017 (Sect. II); numbers marked Heudiasyc from
Bhatt et al. 2017 (Sect. 5.2). The others are ours and say so.
"""

from __future__ import annotations

import enum

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.bus.services import VEHICLE_STACK
from coopdrive.can.adapter import VehicleCanPath
from coopdrive.can.vehicle_port import VehicleCanPortConfig
from coopdrive.runtime.service import ServiceConfig
from coopdrive.v1 import ego_pb2


class PedalProfile(BaseModel):
    """How a unique reference r in [-1, 1] reaches the pedals (DRIVERTIVE Fig. 4), and what r means."""

    model_config = ConfigDict(extra="forbid")

    name: str
    # Acceleration requested at r = 1 and deceleration at r = -1: the feed-forward scale of r.
    accel_at_full_throttle_mps2: float = Field(gt=0.0)
    decel_at_full_brake_mps2: float = Field(gt=0.0)
    # (eq. 1) V_a = offset + gain * r, (eq. 2) V_a/2 = half that.
    throttle_offset_v: float = Field(default=0.4, ge=0.0)
    throttle_gain_v: float = Field(default=3.2, ge=0.0)
    # (eq. 3) P_b = -gain * r for r in [-1, 0]; the paper gives no unit (calibrated pressure of its Fig. 2).
    brake_pressure_gain: float = Field(default=300.0, ge=0.0)
    # Trucks brake by wire (EBS external brake request): the deceleration signal is the command.
    uses_deceleration_request: bool = False


# DRIVERTIVE limited requests to +-2 m/s2 in software and measured 1.6-1.8 m/s2 at full throttle.
CAR_PEDAL_PROFILE = PedalProfile(name="car", accel_at_full_throttle_mps2=2.0, decel_at_full_brake_mps2=8.0)
# Ours: a loaded tractor-trailer; full throttle about 0.8 m/s2, service brakes 5 m/s2.
TRUCK_PEDAL_PROFILE = PedalProfile(name="truck", accel_at_full_throttle_mps2=0.8, decel_at_full_brake_mps2=5.0,
                                   uses_deceleration_request=True)


class SteeringConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # Citroen C4 (DRIVERTIVE's car) wheelbase.
    wheelbase_m: float = Field(default=2.61, gt=0.0)
    # Ours: inside the DBC range of +-0.7 rad with margin.
    max_road_wheel_angle_rad: float = Field(default=0.6, gt=0.0)
    max_angle_rate_radps: float = Field(default=0.4, gt=0.0)
    # The angle is also limited so that v^2 * curvature stays below this.
    max_lateral_accel_mps2: float = Field(default=3.0, gt=0.0)
    # Overlay torque the steering actuator may use to reach the requested angle.
    torque_limit_nm: float = Field(default=3.0, ge=0.0, le=10.0)
    # Steering-wheel degrees per road-wheel degree, to express the DRIVERTIVE override threshold.
    steering_ratio: float = Field(default=15.0, gt=0.0)
    use_curvature: bool = False


class OverrideConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    # DRIVERTIVE II.B.3.a: steering-wheel position error above 5 deg for at least 500 ms.
    steering_error_deg: float = Field(default=5.0, gt=0.0)
    steering_error_duration_s: float = Field(default=0.5, ge=0.0)
    # The steering actuator reaches a command within this time: the measured angle is compared with every
    # command of that window, so its lag while the automation steers briskly is not read as the driver.
    steering_response_s: float = Field(default=0.35, ge=0.0)
    # DRIVERTIVE II.B.3.b: throttle above 10 % of full depression.
    throttle_pedal_ratio: float = Field(default=0.10, ge=0.0, le=1.0)
    # DRIVERTIVE II.B.3.c: any brake; a pedal ratio above this (sensor noise) ...
    brake_pedal_ratio: float = Field(default=0.02, ge=0.0, le=1.0)
    # ... or brake pressure while automation is not braking ...
    brake_pressure_bar: float = Field(default=2.0, ge=0.0)
    # ... and has not braked for this long (ours: the pressure of its own braking takes time to fall).
    brake_release_grace_s: float = Field(default=0.3, ge=0.0)


# 120 km/h: a platoon at 80 km/h whose leader swings +-10 km/h stays well inside; leaving the range mid-run
# forces a safe stop, so the range must hold the traffic the stack follows, not just its set speed.
MOTORWAY_MAX_SPEED_MPS = 120.0 / 3.6


class ModeRequirements(BaseModel):
    """What must hold to enter and to stay in one automated mode."""

    model_config = ConfigDict(extra="forbid")

    required_services: list[str]
    localisation_modes: list[ego_pb2.LocalisationMode.ValueType]
    v2x_required: bool
    max_speed_mps: float = Field(gt=0.0)
    # Once in the mode, a localisation mode not in the list is ridden out while the ego estimate's position
    # std stays within this (0: never).
    hold_position_std_m: float = Field(default=0.0, ge=0.0)


# An automated mode needs every other service of the vehicle's stack alive.
STACK_UPSTREAM = [name for name in VEHICLE_STACK if name != "actuation"]


class ModesConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    cooperative: ModeRequirements = ModeRequirements(
        required_services=STACK_UPSTREAM,
        localisation_modes=[ego_pb2.LOCALISATION_MODE_GNSS_PRECISE, ego_pb2.LOCALISATION_MODE_GNSS_DEGRADED,
                            ego_pb2.LOCALISATION_MODE_DEAD_RECKONING],
        v2x_required=True, max_speed_mps=MOTORWAY_MAX_SPEED_MPS)
    # Lane-level control needs precise positioning. Heudiasyc's car was limited to 50 km/h in autonomous mode;
    # ours drives motorway platoons, whose speed waves go above the GCDC's 80 km/h (set 50 / 3.6 to reproduce
    # Heudiasyc).
    autonomous: ModeRequirements = ModeRequirements(
        required_services=STACK_UPSTREAM,
        localisation_modes=[ego_pb2.LOCALISATION_MODE_GNSS_PRECISE],
        # Lane-level: a car 1.8 m wide in a 3.5 m lane has 0.85 m either side, about two of these sigmas.
        v2x_required=True, max_speed_mps=MOTORWAY_MAX_SPEED_MPS, hold_position_std_m=0.4)
    # Heudiasyc: non-manual modes are entered stopped or below 10 km/h.
    max_engage_speed_mps: float = Field(default=10.0 / 3.6, ge=0.0)
    # Inputs older than this count as absent.
    input_timeout_s: float = Field(default=0.5, gt=0.0)
    transition_history: int = Field(default=50, ge=1)


class WatchdogConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    command_timeout_s: float = Field(default=0.1, gt=0.0)
    critical_services: list[str] = ["planner", "geolocation"]
    max_accel_request_mps2: float = Field(default=4.0, gt=0.0)
    max_decel_request_mps2: float = Field(default=10.0, gt=0.0)
    max_steering_request_rad: float = Field(default=0.7, gt=0.0)
    max_curvature_request_1pm: float = Field(default=0.25, gt=0.0)
    # Controlled stop: the acceleration ramps from the current command to -stop_decel at stop_jerk.
    stop_decel_mps2: float = Field(default=3.0, gt=0.0)
    stop_jerk_mps3: float = Field(default=5.0, gt=0.0)
    estop_decel_mps2: float = Field(default=3.0, gt=0.0)
    estop_jerk_mps3: float = Field(default=10.0, gt=0.0)


class ActuationConfig(BaseModel):
    model_config = ConfigDict(extra="forbid")

    pedal: PedalProfile = CAR_PEDAL_PROFILE
    steering: SteeringConfig = SteeringConfig()
    override: OverrideConfig = OverrideConfig()
    modes: ModesConfig = ModesConfig()
    watchdog: WatchdogConfig = WatchdogConfig()
    # Longest step interval used for rate limits, so a stalled loop cannot cause a jump.
    max_step_s: float = Field(default=0.1, gt=0.0)
    vehicle_id: str = ""

V2X_SERVICE = "v2x"


class EngageMode(enum.Enum):
    NONE = "none"
    COOPERATIVE = "cooperative"
    AUTONOMOUS = "autonomous"


class ActuationServiceConfig(ServiceConfig):
    actuator: ActuationConfig = ActuationConfig()
    # Sim steps are 10 ms; a 20 ms cycle halves the steps this service takes part in.
    rate_hz: float = Field(50.0, gt=0.0)
    status_rate_hz: float = Field(10.0, gt=0.0)
    # The mode requested on every cycle from the start until the actuator accepts it once, as a safety driver
    # pressing "engage" would (simulation runs). On a vehicle it stays none: the driver engages via the gateway.
    engage_on_start: EngageMode = EngageMode.NONE
    # Whether the automated modes need a live v2x service with a healthy V2X status. A stack without a v2x
    # service (the follow run follows by radar alone) sets it false, else no automated mode could be entered.
    require_v2x: bool = True
    # The vehicle's CAN bus (python-can): command frames go out on it and its feedback frames are the
    # vehicle state; actuation owns the car's bus and puts every frame it reads on can/vehicle. None: frames
    # only on can/command, the feedback from can/vehicle (simulation).
    can_port: VehicleCanPortConfig | None = None
    # The car's vehicle CAN adapter (coopdrive/can/adapter.py); None: the simulator's car.
    vehicle_can: VehicleCanPath = None

    def actuator_config(self, vehicle_id: str) -> ActuationConfig:
        config = self.actuator.model_copy(update={"vehicle_id": vehicle_id})
        if self.require_v2x:
            return config
        modes = config.modes.model_copy(update={"cooperative": _without_v2x(config.modes.cooperative),
                                                "autonomous": _without_v2x(config.modes.autonomous)})
        return config.model_copy(update={"modes": modes})


def _without_v2x(requirements: ModeRequirements) -> ModeRequirements:
    return requirements.model_copy(update={
        "v2x_required": False,
        "required_services": [name for name in requirements.required_services if name != V2X_SERVICE]})
