"""Control service: turns the behaviour request and the scene into acceleration and steering requests."""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.v1 import control_pb2, planner_pb2


class ControlConfig(ServiceConfig):
    rate_hz: float = 50.0
    gap_gain_1ps2: float = 0.23
    speed_gain_1ps: float = 0.7
    cruise_gain_1ps: float = 0.4
    comfort_accel_mps2: float = 2.0
    emergency_decel_mps2: float = 8.0
    emergency_ttc_s: float = 1.5


class ControlService(Service):
    name = "control"
    Config = ControlConfig

    def start(self) -> None:
        self.ego = self.scene = self.behaviour = None
        self.ctx.subscribe("ego/state", lambda e: setattr(self, "ego", e.message))
        self.ctx.subscribe("scene", lambda e: setattr(self, "scene", e.message))
        self.ctx.subscribe("planner/behaviour", lambda e: setattr(self, "behaviour", e.message))
        self.ctx.every(1.0 / self.config.rate_hz, self.control)

    def control(self, now_s: float) -> None:
        if self.ego is None or self.behaviour is None:
            return
        c: ControlConfig = self.config
        speed = self.ego.speed_mps
        command = control_pb2.ControlCommand(longitudinal_mode=control_pb2.LONGITUDINAL_MODE_CRUISE,
                                             lateral_mode=control_pb2.LATERAL_MODE_OFF)
        accel = c.cruise_gain_1ps * (self.behaviour.desired_speed_mps - speed)
        target = self._predecessor()
        if target is not None:
            spacing = self.behaviour.spacing
            desired_gap = spacing.standstill_m + spacing.time_gap_s * speed  # d = r + h v
            follow = c.gap_gain_1ps2 * (target.longitudinal_gap_m - desired_gap) + c.speed_gain_1ps * target.relative_speed_mps
            if follow < accel:
                accel = follow
                command.longitudinal_mode = control_pb2.LONGITUDINAL_MODE_ACC
            command.target_object_id, command.gap_m, command.desired_gap_m = target.object_id, target.longitudinal_gap_m, desired_gap
            command.time_gap_s = spacing.time_gap_s
            closing = -target.relative_speed_mps
            if closing > 0 and target.longitudinal_gap_m / closing < c.emergency_ttc_s:
                command.emergency_brake = True
                command.longitudinal_mode = control_pb2.LONGITUDINAL_MODE_EMERGENCY_BRAKE
        low = -c.emergency_decel_mps2 if command.emergency_brake else -c.comfort_accel_mps2
        command.accel_request_mps2 = min(max(accel, low), c.comfort_accel_mps2)
        command.cruise_speed_mps = self.behaviour.desired_speed_mps
        self.ctx.publish("control/command", command, sample_time_s=self.ego.header.sample_time_s)

    def _predecessor(self):
        if self.scene is None:
            return None
        wanted = {t.object_id for t in self.behaviour.targets if t.role == planner_pb2.TARGET_ROLE_PREDECESSOR}
        return next((o for o in self.scene.objects if o.object_id in wanted), None)
