"""Watchdog and StopRamp: stale, invalid or orphaned control -> a controlled stop with hazard lights.

The watchdog validates every control command and notices when commands stop coming (older than 100 ms) or
when a service the commands depend on dies. The stop ramps the acceleration down from the last applied
command at a limited jerk to the configured deceleration, never loosening a harder braking already applied.
"""

import enum
import math

from coopdrive.reasons import Reasoned
from coopdrive.services.actuation.config import WatchdogConfig
from coopdrive.v1 import control_pb2


class StopCause(enum.Enum):
    COMMAND_TIMEOUT = "control command too old"
    SERVICE_DEAD = "critical service not alive"
    INVALID_COMMAND = "invalid control command"
    EMERGENCY_STOP = "emergency stop"
    REQUESTED = "safe stop requested"


class StopTrigger(Reasoned[StopCause]):
    """What starts a controlled stop."""


def command_problem(cmd: control_pb2.ControlCommand, config: WatchdogConfig) -> str | None:
    """What makes a control command unusable, None when it is usable."""
    checks = (
        ("accel_request_mps2", cmd.accel_request_mps2, -config.max_decel_request_mps2, config.max_accel_request_mps2),
        ("steering_angle_request_rad", cmd.steering_angle_request_rad,
         -config.max_steering_request_rad, config.max_steering_request_rad),
        ("curvature_request_1pm", cmd.curvature_request_1pm,
         -config.max_curvature_request_1pm, config.max_curvature_request_1pm),
    )
    for name, value, low, high in checks:
        if not math.isfinite(value):
            return f"{name} is {value}"
        if not low <= value <= high:
            return f"{name} = {value} outside [{low}, {high}]"
    return None


class Watchdog:
    def __init__(self, config: WatchdogConfig):
        self.config = config
        self.last_valid_command: control_pb2.ControlCommand | None = None
        self.last_valid_command_s: float | None = None
        self.commands_rejected = 0
        self._alive: dict[str, bool] = {}
        self._pending: StopTrigger | None = None

    def on_command(self, cmd: control_pb2.ControlCommand, now_s: float) -> StopTrigger | None:
        """Accepts a valid command; an invalid one is counted, dropped and returned as a stop trigger."""
        problem = command_problem(cmd, self.config)
        if problem is None and cmd.header.sample_time_s > 0.0 \
                and now_s - cmd.header.sample_time_s > self.config.command_timeout_s:
            problem = f"sampled {now_s - cmd.header.sample_time_s:.3f} s ago"
        if problem is not None:
            self.commands_rejected += 1
            self._pending = StopTrigger(StopCause.INVALID_COMMAND, problem)
            return self._pending
        self.last_valid_command = cmd
        self.last_valid_command_s = now_s
        return None

    def set_service_alive(self, name: str, alive: bool) -> None:
        self._alive[name] = alive

    def command_fresh(self, now_s: float) -> bool:
        return self.last_valid_command_s is not None \
            and now_s - self.last_valid_command_s <= self.config.command_timeout_s

    def check(self, now_s: float) -> StopTrigger | None:
        """Why the automation must stop now, None when all is well; a pending invalid command is reported once."""
        if self._pending is not None:
            trigger, self._pending = self._pending, None
            return trigger
        if not self.command_fresh(now_s):
            age = "none received" if self.last_valid_command_s is None \
                else f"last valid {now_s - self.last_valid_command_s:.3f} s ago"
            return StopTrigger(StopCause.COMMAND_TIMEOUT, age)
        for name in self.config.critical_services:
            if not self._alive.get(name, False):
                return StopTrigger(StopCause.SERVICE_DEAD, name)
        return None

    def clear(self) -> None:
        """Forget a pending trigger, e.g. one raised while the automation was not engaged."""
        self._pending = None

    def ramp(self, start_accel_mps2: float, emergency: bool) -> "StopRamp":
        c = self.config
        if emergency:
            return StopRamp(start_accel_mps2, c.estop_decel_mps2, c.estop_jerk_mps3)
        return StopRamp(start_accel_mps2, c.stop_decel_mps2, c.stop_jerk_mps3)


class StopRamp:
    """Acceleration of a controlled stop: from the current command down to -decel at a bounded jerk.

    The deceleration is kept at standstill, so the brake holds the vehicle until the driver takes over.
    """

    def __init__(self, start_accel_mps2: float, decel_mps2: float, jerk_mps3: float):
        self.accel_mps2 = start_accel_mps2
        self.jerk_mps3 = jerk_mps3
        # Braking harder than the stop deceleration when the stop begins is kept, not released.
        self.target_mps2 = min(start_accel_mps2, -decel_mps2)

    def step(self, dt_s: float) -> float:
        self.accel_mps2 = max(self.target_mps2, self.accel_mps2 - self.jerk_mps3 * max(dt_s, 0.0))
        return self.accel_mps2
