"""DrivingModeManager: manual / cooperative / autonomous / safe stop, after Heudiasyc Sect. 5.2.

A non-manual mode is entered only on request and only when every activation condition holds; the first unmet
condition is named in the refusal. The conditions are checked again on every `update`: when one stops holding
in an automated mode, the manager forces a controlled stop (the safety driver can take over at any moment).
Supervision (the watchdog, driver overrides) can force any mode; every forced transition is logged.
"""

import enum
import logging
import math
from collections import deque
from dataclasses import dataclass

from coopdrive.reasons import Reasoned
from coopdrive.services.actuation.config import ModeRequirements, ModesConfig
from coopdrive.v1 import actuation_pb2, ego_pb2, vehicle_pb2

log = logging.getLogger(__name__)

DrivingMode = actuation_pb2.DrivingMode
MANUAL = actuation_pb2.DRIVING_MODE_MANUAL
COOPERATIVE = actuation_pb2.DRIVING_MODE_COOPERATIVE
AUTONOMOUS = actuation_pb2.DRIVING_MODE_AUTONOMOUS
SAFE_STOP = actuation_pb2.DRIVING_MODE_SAFE_STOP
AUTOMATED_MODES = (COOPERATIVE, AUTONOMOUS)
# Modes in which the automation drives at least the pedals.
ENGAGED_MODES = (COOPERATIVE, AUTONOMOUS, SAFE_STOP)


def mode_name(mode: DrivingMode.ValueType) -> str:
    return DrivingMode.Name(mode).removeprefix("DRIVING_MODE_").lower()


class Condition(enum.Enum):
    KNOWN_MODE = "a known mode was requested"
    VEHICLE_STATE = "vehicle state received"
    GEAR = "gear in drive"
    NO_DRIVER_INPUT = "driver not pressing a pedal"
    ENGAGE_SPEED = "slow enough to engage"
    SPEED_IN_RANGE = "speed in range"
    SERVICES_ALIVE = "needed services alive"
    LOCALISATION = "localisation good enough"
    V2X_HEALTHY = "V2X healthy"
    CONTROL_COMMAND = "fresh control command"


class UnmetCondition(Reasoned[Condition]):
    """The first activation condition that does not hold."""


@dataclass(frozen=True)
class ModeTransition:
    time_s: float
    from_mode: DrivingMode.ValueType
    to_mode: DrivingMode.ValueType
    reason: str
    forced: bool


@dataclass(frozen=True)
class ModeDecision:
    accepted: bool
    mode: DrivingMode.ValueType
    unmet: UnmetCondition | None = None


class DrivingModeManager:
    def __init__(self, config: ModesConfig, command_timeout_s: float):
        self.config = config
        self.command_timeout_s = command_timeout_s
        self.mode: DrivingMode.ValueType = MANUAL
        self.last_change_reason = "start"
        self.transitions: deque[ModeTransition] = deque(maxlen=config.transition_history)
        self._alive: dict[str, bool] = {}
        # (localisation mode, the estimate's position std, when)
        self._localisation: tuple[ego_pb2.LocalisationMode.ValueType, float, float] | None = None
        self._v2x: tuple[bool, float] | None = None
        self._vehicle: tuple[float, vehicle_pb2.Gear.ValueType, float] | None = None
        self._last_command_s: float | None = None
        self._driver_input: str | None = None

    # ---- inputs --------------------------------------------------------------------------------------------

    def set_service_alive(self, name: str, alive: bool) -> None:
        self._alive[name] = alive

    def set_localisation_mode(self, mode: ego_pb2.LocalisationMode.ValueType, now_s: float,
                              position_std_m: float = math.inf) -> None:
        self._localisation = (mode, position_std_m, now_s)

    def set_v2x_healthy(self, healthy: bool, now_s: float) -> None:
        self._v2x = (healthy, now_s)

    def set_vehicle_state(self, speed_mps: float, gear: vehicle_pb2.Gear.ValueType, now_s: float) -> None:
        self._vehicle = (speed_mps, gear, now_s)

    def set_control_command_time(self, now_s: float) -> None:
        self._last_command_s = now_s

    def set_driver_input(self, description: str | None) -> None:
        """What the driver is doing on the pedals right now, None when nothing."""
        self._driver_input = description

    # ---- conditions ----------------------------------------------------------------------------------------

    def requirements(self, mode: DrivingMode.ValueType) -> ModeRequirements:
        return self.config.cooperative if mode == COOPERATIVE else self.config.autonomous

    def unmet_condition(self, mode: DrivingMode.ValueType, now_s: float, engaging: bool) -> UnmetCondition | None:
        """The first activation condition of `mode` that does not hold now; None when all hold."""
        if mode not in AUTOMATED_MODES:
            return UnmetCondition(Condition.KNOWN_MODE, f"{mode_name(mode)} has no activation conditions")
        need = self.requirements(mode)
        timeout_s = self.config.input_timeout_s
        if self._vehicle is None or now_s - self._vehicle[2] > timeout_s:
            return UnmetCondition(Condition.VEHICLE_STATE, f"none in the last {timeout_s} s")
        speed_mps, gear, _ = self._vehicle
        if gear != vehicle_pb2.GEAR_DRIVE:
            return UnmetCondition(Condition.GEAR, f"gear is {vehicle_pb2.Gear.Name(gear)}")
        if engaging and self._driver_input is not None:
            return UnmetCondition(Condition.NO_DRIVER_INPUT, self._driver_input)
        if engaging and speed_mps > self.config.max_engage_speed_mps:
            return UnmetCondition(Condition.ENGAGE_SPEED,
                                  f"{speed_mps:.2f} m/s > {self.config.max_engage_speed_mps:.2f} m/s")
        if speed_mps > need.max_speed_mps:
            return UnmetCondition(Condition.SPEED_IN_RANGE, f"{speed_mps:.2f} m/s > {need.max_speed_mps:.2f} m/s")
        for name in need.required_services:
            if not self._alive.get(name, False):
                return UnmetCondition(Condition.SERVICES_ALIVE, f"{name} not alive")
        unmet = self._localisation_unmet(need, now_s, engaging) or self._v2x_unmet(need, now_s)
        if unmet is not None:
            return unmet
        if self._last_command_s is None or now_s - self._last_command_s > self.command_timeout_s:
            return UnmetCondition(Condition.CONTROL_COMMAND, f"none valid in the last {self.command_timeout_s} s")
        return None

    def _localisation_unmet(self, need: ModeRequirements, now_s: float, engaging: bool) -> UnmetCondition | None:
        if self._localisation is None or now_s - self._localisation[2] > self.config.input_timeout_s:
            return UnmetCondition(Condition.LOCALISATION, f"no ego state in the last {self.config.input_timeout_s} s")
        mode, position_std_m, _ = self._localisation
        # Once engaged, a short loss of RTK or a multipath jump the filter refused is ridden out while the
        # estimate itself stays as good as the mode needs.
        held = not engaging and mode != ego_pb2.LOCALISATION_MODE_LOST and position_std_m <= need.hold_position_std_m
        if mode not in need.localisation_modes and not held:
            return UnmetCondition(Condition.LOCALISATION, f"{ego_pb2.LocalisationMode.Name(mode)} not accepted")
        return None

    def _v2x_unmet(self, need: ModeRequirements, now_s: float) -> UnmetCondition | None:
        if not need.v2x_required:
            return None
        if self._v2x is None or now_s - self._v2x[1] > self.config.input_timeout_s:
            return UnmetCondition(Condition.V2X_HEALTHY, f"no V2X status in the last {self.config.input_timeout_s} s")
        if not self._v2x[0]:
            return UnmetCondition(Condition.V2X_HEALTHY, "V2X reports unhealthy")
        return None

    def availability(self, now_s: float) -> list[actuation_pb2.ModeAvailability]:
        result = [actuation_pb2.ModeAvailability(mode=MANUAL, available=True)]
        for mode in AUTOMATED_MODES:
            unmet = self.unmet_condition(mode, now_s, engaging=self.mode not in AUTOMATED_MODES)
            result.append(actuation_pb2.ModeAvailability(mode=mode, available=unmet is None,
                                                         unmet_condition="" if unmet is None else str(unmet)))
        return result

    # ---- transitions ---------------------------------------------------------------------------------------

    def request(self, mode: DrivingMode.ValueType, now_s: float, requested_by: str = "") -> ModeDecision:
        who = f" by {requested_by}" if requested_by else ""
        if mode in (MANUAL, SAFE_STOP):
            self._change(mode, f"requested{who}", now_s, forced=False)
            return ModeDecision(True, mode)
        if mode == self.mode:
            return ModeDecision(True, mode)
        unmet = self.unmet_condition(mode, now_s, engaging=self.mode not in AUTOMATED_MODES)
        if unmet is not None:
            log.info("refused %s%s: %s", mode_name(mode), who, unmet)
            return ModeDecision(False, self.mode, unmet)
        self._change(mode, f"requested{who}", now_s, forced=False)
        return ModeDecision(True, mode)

    def force(self, mode: DrivingMode.ValueType, reason: str, now_s: float) -> None:
        """Supervision's transition, whatever the conditions."""
        if mode != self.mode:
            self._change(mode, reason, now_s, forced=True)

    def update(self, now_s: float) -> ModeTransition | None:
        """Re-checks the conditions of the current automated mode; forces a safe stop when one fails."""
        if self.mode not in AUTOMATED_MODES:
            return None
        unmet = self.unmet_condition(self.mode, now_s, engaging=False)
        if unmet is None:
            return None
        self.force(SAFE_STOP, f"{mode_name(self.mode)} condition lost: {unmet}", now_s)
        return self.transitions[-1]

    def _change(self, mode: DrivingMode.ValueType, reason: str, now_s: float, forced: bool) -> None:
        transition = ModeTransition(now_s, self.mode, mode, reason, forced)
        if forced:
            log.warning("forced %s -> %s: %s", mode_name(self.mode), mode_name(mode), reason)
        else:
            log.info("%s -> %s: %s", mode_name(self.mode), mode_name(mode), reason)
        self.transitions.append(transition)
        self.mode = mode
        self.last_change_reason = reason
