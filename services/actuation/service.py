"""Actuation service: the only door to the vehicle. Maps requests to pedals and steering, stops safely."""

from __future__ import annotations

import math

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.v1 import actuation_pb2


class ActuationConfig(ServiceConfig):
    rate_hz: float = 100.0
    status_rate_hz: float = 10.0
    command_timeout_s: float = 0.1
    safe_stop_decel_mps2: float = 3.0
    max_throttle_accel_mps2: float = 3.0
    max_brake_decel_mps2: float = 8.0
    max_command_accel_mps2: float = 10.0
    initial_mode: str = "autonomous"


class ActuationService(Service):
    name = "actuation"
    Config = ActuationConfig

    def start(self) -> None:
        self.command = None
        self.mode = actuation_pb2.DRIVING_MODE_AUTONOMOUS
        self.mode_reason = "initial mode from config"
        self.last_accel_mps2 = 0.0
        self.ctx.subscribe("control/command", self.on_control_command)
        self.ctx.every(1.0 / self.config.rate_hz, self.actuate)
        self.ctx.every(1.0 / self.config.status_rate_hz, self.publish_status)

    def on_control_command(self, envelope: Envelope) -> None:
        command = envelope.message
        if not math.isfinite(command.accel_request_mps2) or abs(command.accel_request_mps2) > self.config.max_command_accel_mps2:
            self.count("rejected_commands")
            return
        self.command = command

    def actuate(self, now_s: float) -> None:
        c: ActuationConfig = self.config
        stale = self.command is None or now_s - self.command.header.sent_time_s > c.command_timeout_s
        if stale and self.command is not None:
            if self.mode != actuation_pb2.DRIVING_MODE_SAFE_STOP:
                self.mode, self.mode_reason = actuation_pb2.DRIVING_MODE_SAFE_STOP, "control commands stale"
                self.count("watchdog_stops")
            accel = max(-c.safe_stop_decel_mps2, self.last_accel_mps2 - c.safe_stop_decel_mps2 / c.rate_hz)
        elif self.command is None:
            accel = 0.0
        else:
            accel = self.command.accel_request_mps2
        self.last_accel_mps2 = accel
        out = actuation_pb2.ActuatorCommand(
            accel_request_mps2=accel, throttle_ratio=max(accel, 0.0) / c.max_throttle_accel_mps2,
            brake_ratio=max(-accel, 0.0) / c.max_brake_decel_mps2,
            steering_angle_rad=0.0 if self.command is None else self.command.steering_angle_request_rad,
            hazard_lights=self.mode == actuation_pb2.DRIVING_MODE_SAFE_STOP, automation_active=True)
        self.ctx.publish("actuation/command", out)

    def publish_status(self, now_s: float) -> None:
        status = actuation_pb2.ActuationStatus(mode=self.mode, last_mode_change_reason=self.mode_reason)
        self.ctx.publish("actuation/status", status)
