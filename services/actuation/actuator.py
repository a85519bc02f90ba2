"""Actuator: control commands, vehicle state and supervision in; CAN command frames and status out.

Combines the pedal and steering maps, the driver override detector, the driving mode manager and the
watchdog. Every `step` emits the ACT_ frames due at their DBC cycle times (and any that changed), also in
manual mode (inactive), so the vehicle side always sees a live, counted stream.
"""


import can

from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.can.send_schedule import CyclicSendSchedule
from coopdrive.services.actuation import modes as m
from coopdrive.services.actuation.config import ActuationConfig
from coopdrive.services.actuation.modes import DrivingModeManager, ModeDecision
from coopdrive.services.actuation.override import DriverOverrideDetector, OverrideDetection
from coopdrive.services.actuation.pedal_map import PedalMap
from coopdrive.services.actuation.steering_map import SteeringMap
from coopdrive.services.actuation.watchdog import StopCause, StopRamp, StopTrigger, Watchdog
from coopdrive.v1 import actuation_pb2, control_pb2, ego_pb2, vehicle_pb2

SENDER = "actuation"


class Actuator:
    def __init__(self, config: ActuationConfig | None = None, codec: VehicleCanCodec | None = None):
        self.config = config or ActuationConfig()
        self.codec = codec or VehicleCanCodec()
        # Each ACT_ frame at its DBC cycle time, and at once when it changes: the body frame mostly at 10 Hz.
        self._send_schedule = CyclicSendSchedule()
        self.pedals = PedalMap(self.config.pedal)
        self.steering = SteeringMap(self.config.steering)
        self.overrides = DriverOverrideDetector(self.config.override, self.config.steering.steering_ratio)
        self.watchdog = Watchdog(self.config.watchdog)
        self.modes = DrivingModeManager(self.config.modes, self.config.watchdog.command_timeout_s)
        self.frames_sent = 0
        self.frames_rejected = 0
        self._ramp: StopRamp | None = None
        self._stop_steers = False
        self._speed_mps = 0.0
        self._measured_angle_rad = 0.0
        self._accel_mps2 = 0.0
        self._angle_rad = 0.0
        self._braking = False
        self._last_step_s: float | None = None
        self._indicators = (False, False)
        self._override_events: list[actuation_pb2.OverrideEvent] = []
        self._sequence = 0
        # The command of the last step, and the acceleration its pedals were mapped from.
        self.last_command: VehicleCommand | None = None

    @property
    def accel_request_mps2(self) -> float:
        """The acceleration the last step's pedals stand for (after ramps), m/s^2."""
        return self._accel_mps2

    @property
    def mode(self) -> actuation_pb2.DrivingMode.ValueType:
        return self.modes.mode

    # ---- inputs --------------------------------------------------------------------------------------------

    def on_control_command(self, cmd: control_pb2.ControlCommand, now_s: float) -> bool:
        """False when the command was rejected (NaN, out of range, stale); engaged, that starts a safe stop."""
        trigger = self.watchdog.on_command(cmd, now_s)
        if trigger is not None:
            self.frames_rejected += 1
            if self.mode in m.AUTOMATED_MODES:
                self._start_stop(trigger, now_s)
            else:
                self.watchdog.clear()
            return False
        self.modes.set_control_command_time(now_s)
        return True

    def on_vehicle_state(self, state: vehicle_pb2.VehicleCanState, now_s: float) -> OverrideDetection | None:
        """Feeds speed, gear and driver action; returns a driver override when this state reveals one."""
        self._speed_mps = (state.wheel_speed_rear_left_mps + state.wheel_speed_rear_right_mps) / 2.0
        self._measured_angle_rad = state.steering_angle_rad
        self.modes.set_vehicle_state(self._speed_mps, state.gear, now_s)
        engaged = self.mode in m.ENGAGED_MODES
        pedal = self.overrides.pedal_input(state, automation_braking=self._braking and engaged)
        self.modes.set_driver_input(None if pedal is None else
                                    f"{actuation_pb2.OverrideReason.Name(pedal.reason)} at {pedal.value:.2f}")
        detection = self.overrides.update(
            state, now_s, longitudinal_engaged=engaged, lateral_engaged=self._lateral_engaged(),
            commanded_angle_rad=self._angle_rad, automation_braking=self._braking)
        if detection is not None:
            reason = actuation_pb2.OverrideReason.Name(detection.reason)
            self.modes.force(m.MANUAL, f"driver override: {reason} ({detection.value:.2f})", now_s)
            self._ramp = None
            event = actuation_pb2.OverrideEvent(reason=detection.reason, value=detection.value)
            self._fill_header(event.header, now_s)
            self._override_events.append(event)
        return detection

    def on_ego_state(self, ego: ego_pb2.EgoState, now_s: float) -> None:
        self.modes.set_localisation_mode(ego.mode, now_s, ego.position_std_m)

    def on_v2x_health(self, healthy: bool, now_s: float) -> None:
        self.modes.set_v2x_healthy(healthy, now_s)

    def on_service_liveness(self, name: str, alive: bool) -> None:
        self.modes.set_service_alive(name, alive)
        self.watchdog.set_service_alive(name, alive)

    def on_turn_indicators(self, left: bool, right: bool) -> None:
        """The planner's intention; shown only while the automation drives."""
        self._indicators = (left, right)

    def on_mode_request(self, req: actuation_pb2.ModeRequest, now_s: float) -> ModeDecision:
        if req.mode == m.SAFE_STOP:
            self._start_stop(StopTrigger(StopCause.REQUESTED, req.requested_by or "unspecified"),
                             now_s, emergency=False)
            return ModeDecision(True, self.mode)
        decision = self.modes.request(req.mode, now_s, req.requested_by)
        if decision.accepted and req.mode in m.AUTOMATED_MODES:
            self.overrides.rearm()
            self.watchdog.clear()
            self._ramp = None
        if decision.accepted and req.mode == m.MANUAL:
            self._ramp = None
        return decision

    def on_estop(self, now_s: float, requested_by: str = "") -> None:
        """Emergency stop: the controlled stop starts now, in any mode, at the emergency rates."""
        self._start_stop(StopTrigger(StopCause.EMERGENCY_STOP, requested_by or "unspecified"), now_s, emergency=True)

    def take_override_events(self) -> list[actuation_pb2.OverrideEvent]:
        events, self._override_events = self._override_events, []
        return events

    # ---- the cycle -----------------------------------------------------------------------------------------

    def step(self, now_s: float) -> tuple[list[can.Message], actuation_pb2.ActuationStatus]:
        dt_s = 0.0 if self._last_step_s is None else min(max(now_s - self._last_step_s, 0.0), self.config.max_step_s)
        self._last_step_s = now_s
        if self.mode in m.AUTOMATED_MODES:
            trigger = self.watchdog.check(now_s)
            if trigger is not None:
                self._start_stop(trigger, now_s)
        transition = self.modes.update(now_s)
        if transition is not None:
            self._stop_steers = transition.from_mode == m.AUTONOMOUS
            self._ramp = self.watchdog.ramp(self._accel_mps2, emergency=False)
        command = self._command(dt_s)
        self.last_command = command
        frames = self.codec.encode_vehicle_command(command, timestamp_s=now_s, schedule=self._send_schedule)
        self.frames_sent += len(frames)
        return frames, self._status(command, now_s)

    def _command(self, dt_s: float) -> VehicleCommand:
        mode = self.mode
        cmd = self.watchdog.last_valid_command
        if mode == m.MANUAL or cmd is None and self._ramp is None:
            self._accel_mps2, self._angle_rad, self._braking = 0.0, self._measured_angle_rad, False
            return VehicleCommand(driving_mode=mode)
        if self._ramp is not None:
            accel = self._ramp.step(dt_s)
        else:
            accel = cmd.accel_request_mps2
        lateral = self._lateral_engaged()
        if lateral:
            target = self._angle_rad
            if cmd is not None and (mode == m.AUTONOMOUS or self.watchdog.command_fresh(self._last_step_s)):
                target = self.steering.target_angle_rad(cmd.steering_angle_request_rad, cmd.curvature_request_1pm)
            angle = self.steering.map(target, self._angle_rad, self._speed_mps, dt_s).angle_rad
        else:
            angle = self._measured_angle_rad
        pedals = self.pedals.map(accel)
        self._accel_mps2, self._angle_rad, self._braking = accel, angle, pedals.reference < 0.0
        stopping = mode == m.SAFE_STOP
        left, right = self._indicators if not stopping else (False, False)
        return VehicleCommand(
            throttle_ratio=pedals.throttle_ratio, brake_ratio=pedals.brake_ratio,
            deceleration_request_mps2=pedals.deceleration_request_mps2, longitudinal_active=True,
            steering_angle_request_rad=angle, steering_torque_request_nm=self.config.steering.torque_limit_nm
            if lateral else 0.0, lateral_active=lateral,
            indicator_left=left, indicator_right=right, hazard_lights=stopping, automation_active=True,
            driving_mode=mode)

    def _lateral_engaged(self) -> bool:
        return self.mode == m.AUTONOMOUS or (self.mode == m.SAFE_STOP and self._stop_steers)

    def _start_stop(self, trigger: StopTrigger, now_s: float, emergency: bool = False) -> None:
        """Forces a safe stop; a stop already under way continues unless an emergency makes it harder."""
        if self.mode == m.SAFE_STOP and self._ramp is not None and not emergency:
            return
        if self.mode == m.MANUAL:
            # The driver must be able to override this stop even after overriding the automation earlier.
            self.overrides.rearm()
        if self.mode != m.SAFE_STOP:
            self._stop_steers = self.mode == m.AUTONOMOUS
        self.modes.force(m.SAFE_STOP, str(trigger), now_s)
        self._ramp = self.watchdog.ramp(self._accel_mps2, emergency)

    # ---- output --------------------------------------------------------------------------------------------

    def _fill_header(self, header, now_s: float) -> None:
        self._sequence += 1
        header.sample_time_s = now_s
        header.sent_time_s = now_s
        header.sender = SENDER
        header.vehicle_id = self.config.vehicle_id
        header.sequence = self._sequence

    def actuator_command(self, now_s: float):
        """The last step's command as a coopdrive.v1 ActuatorCommand (for the bus and the simulator), or None."""
        command = self.last_command
        if command is None:
            return None
        out = actuation_pb2.ActuatorCommand(
            throttle_ratio=command.throttle_ratio, brake_ratio=command.brake_ratio,
            steering_angle_rad=command.steering_angle_request_rad, accel_request_mps2=self._accel_mps2,
            indicator_left=command.indicator_left, indicator_right=command.indicator_right,
            hazard_lights=command.hazard_lights, automation_active=command.automation_active)
        self._fill_header(out.header, now_s)
        return out

    def _status(self, command: VehicleCommand, now_s: float) -> actuation_pb2.ActuationStatus:
        status = actuation_pb2.ActuationStatus(
            mode=self.mode, throttle_ratio=command.throttle_ratio, brake_ratio=command.brake_ratio,
            steering_angle_rad=command.steering_angle_request_rad, indicator_left=command.indicator_left,
            indicator_right=command.indicator_right, hazard_lights=command.hazard_lights,
            availability=self.modes.availability(now_s), last_mode_change_reason=self.modes.last_change_reason,
            frames_sent=self.frames_sent, frames_rejected=self.frames_rejected)
        self._fill_header(status.header, now_s)
        return status
