"""DriverOverrideDetector: the driver takes over through the wheel, the throttle or the brake.

DRIVERTIVE Sect. II.B.3: a steering-wheel position error above 5 deg for 500 ms, a throttle above 10 %, or
any brake (pedal pressed, or brake pressure while the automation is not braking). The steering error is the
distance from the measured angle to the commands of the last steering_response_s: an actuator still on its
way to a command is following it, a driver holding the wheel away from all of them is not. Heudiasyc Sect. 5.2: in
cooperative mode only the automated sub-system (here longitudinal) is watched. Once it fires the detector
stays latched: automation re-engages only when the driver asks again (`rearm`).
"""

import math
from collections import deque
from dataclasses import dataclass

from coopdrive.services.actuation.config import OverrideConfig
from coopdrive.v1 import actuation_pb2, vehicle_pb2

OverrideReason = actuation_pb2.OverrideReason


@dataclass(frozen=True)
class OverrideDetection:
    reason: OverrideReason.ValueType
    # The offending measurement: steering-wheel error in deg, pedal ratio, or brake pressure in bar.
    value: float


class DriverOverrideDetector:
    def __init__(self, config: OverrideConfig, steering_ratio: float):
        self.config = config
        self.steering_ratio = steering_ratio
        self.latched: OverrideDetection | None = None
        self._steering_error_since_s: float | None = None
        self._last_braking_s: float | None = None
        self._recent_commands: deque[tuple[float, float]] = deque()

    def steering_wheel_error_deg(self, measured_angle_rad: float, commanded_angle_rad: float) -> float:
        return abs(math.degrees(measured_angle_rad - commanded_angle_rad)) * self.steering_ratio

    def pedal_input(self, state: vehicle_pb2.VehicleCanState, automation_braking: bool,
                    now_s: float | None = None) -> OverrideDetection | None:
        """The driver's throttle or brake action in this state, steering aside."""
        if automation_braking and now_s is not None:
            self._last_braking_s = now_s
        releasing = self._last_braking_s is not None and now_s is not None \
            and now_s - self._last_braking_s < self.config.brake_release_grace_s
        if state.throttle_pedal_ratio > self.config.throttle_pedal_ratio:
            return OverrideDetection(actuation_pb2.OVERRIDE_REASON_THROTTLE, state.throttle_pedal_ratio)
        if state.brake_pedal_ratio > self.config.brake_pedal_ratio:
            return OverrideDetection(actuation_pb2.OVERRIDE_REASON_BRAKE, state.brake_pedal_ratio)
        # While the automation brakes, pressure is its own; DRIVERTIVE caught the driver when r(k) >= 0 again.
        if not (automation_braking or releasing) and state.brake_pressure_bar > self.config.brake_pressure_bar:
            return OverrideDetection(actuation_pb2.OVERRIDE_REASON_BRAKE, state.brake_pressure_bar)
        return None

    def update(self, state: vehicle_pb2.VehicleCanState, now_s: float, *, longitudinal_engaged: bool,
               lateral_engaged: bool, commanded_angle_rad: float,
               automation_braking: bool) -> OverrideDetection | None:
        """The override detected by this state, once; None while latched, disengaged or undisturbed."""
        if self.latched is not None or not (longitudinal_engaged or lateral_engaged):
            self._steering_error_since_s = None
            return None
        detection = self.pedal_input(state, automation_braking, now_s) if longitudinal_engaged else None
        if detection is None and lateral_engaged:
            detection = self._steering(state, now_s, commanded_angle_rad)
        elif not lateral_engaged:
            self._steering_error_since_s = None
        if detection is not None:
            self.latched = detection
            self._steering_error_since_s = None
        return detection

    def _remember_command(self, now_s: float, commanded_rad: float) -> None:
        recent = self._recent_commands
        recent.append((now_s, commanded_rad))
        while len(recent) > 1 and recent[0][0] < now_s - self.config.steering_response_s:
            recent.popleft()

    def _nearest_recent_command_rad(self, measured_rad: float) -> float:
        low = min(angle for _, angle in self._recent_commands)
        high = max(angle for _, angle in self._recent_commands)
        return min(max(measured_rad, low), high)

    def _steering(self, state: vehicle_pb2.VehicleCanState, now_s: float,
                  commanded_angle_rad: float) -> OverrideDetection | None:
        self._remember_command(now_s, commanded_angle_rad)
        followed_rad = self._nearest_recent_command_rad(state.steering_angle_rad)
        error_deg = self.steering_wheel_error_deg(state.steering_angle_rad, followed_rad)
        if error_deg <= self.config.steering_error_deg:
            self._steering_error_since_s = None
            return None
        if self._steering_error_since_s is None:
            self._steering_error_since_s = now_s
        if now_s - self._steering_error_since_s >= self.config.steering_error_duration_s:
            return OverrideDetection(actuation_pb2.OVERRIDE_REASON_STEERING, error_deg)
        return None

    def rearm(self) -> None:
        """The driver asked for automation again."""
        self.latched = None
        self._steering_error_since_s = None
        self._recent_commands.clear()
