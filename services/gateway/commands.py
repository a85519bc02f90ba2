"""CommandDesk: turns authenticated commands into bus messages and logs who asked and why.

It never publishes itself: `submit` hands a function to the service's worker thread
(ctx.call_soon), which is the only thread that publishes.
"""

from __future__ import annotations

import logging
import threading
from collections import deque
from enum import Enum
from typing import Callable

from pydantic import BaseModel, Field

from coopdrive.services.gateway.auth import Command, Principal
from coopdrive.v1 import actuation_pb2

MAX_REASON_CHARS = 500
PLANNER_FORCE_TOPIC = "gateway/planner_force"
# Commands remembered for GET /commands.
AUDIT_LENGTH = 100


class RequestedMode(str, Enum):
    MANUAL = "manual"
    COOPERATIVE = "cooperative"
    AUTONOMOUS = "autonomous"


MODES = {RequestedMode.MANUAL: actuation_pb2.DRIVING_MODE_MANUAL,
         RequestedMode.COOPERATIVE: actuation_pb2.DRIVING_MODE_COOPERATIVE,
         RequestedMode.AUTONOMOUS: actuation_pb2.DRIVING_MODE_AUTONOMOUS}


class Reasoned(BaseModel):
    reason: str = Field(min_length=1, max_length=MAX_REASON_CHARS,
                        description="Why the command is given; logged with the token's name.")


class ModeCommand(Reasoned):
    mode: RequestedMode


class EstopCommand(Reasoned):
    pass


class PlannerForceCommand(Reasoned):
    state: str = Field(min_length=1, description="The state to put the planner's machine in, by name.")


class RecordingAction(str, Enum):
    START = "start"
    STOP = "stop"


class RecordingCommand(Reasoned):
    action: RecordingAction


class CommandOutcome(str, Enum):
    SENT = "sent"  # handed to the bus; the receiving service decides (see /state actuation_status)
    DONE = "done"  # carried out by the gateway itself (recording)
    REFUSED = "refused"  # not carried out; detail says why


class CommandResponse(BaseModel):
    command: Command
    outcome: CommandOutcome
    requested_by: str
    reason: str
    detail: str = ""


class CommandDesk:
    def __init__(self, run_on_worker: Callable[[Callable[[], None]], None], log: logging.Logger,
                 count: Callable[[Command, CommandOutcome], None] = lambda command, outcome: None):
        self._run_on_worker = run_on_worker
        self._log = log
        self._count = count
        self._lock = threading.Lock()
        self._audit: deque[CommandResponse] = deque(maxlen=AUDIT_LENGTH)

    def record(self, command: Command, who: Principal, reason: str, outcome: CommandOutcome,
               detail: str = "") -> CommandResponse:
        response = CommandResponse(command=command, outcome=outcome, requested_by=who.name, reason=reason,
                                   detail=detail)
        self._log.warning("command %s by %s (%s): %s%s; reason: %s", command.value, who.name, who.role.value,
                          outcome.value, f" ({detail})" if detail else "", reason)
        with self._lock:
            self._audit.append(response)
        self._count(command, outcome)
        return response

    def recent(self) -> list[CommandResponse]:
        with self._lock:
            return list(self._audit)

    def mode(self, who: Principal, body: ModeCommand, publish: Callable[[str, object], None],
             status: actuation_pb2.ActuationStatus | None = None) -> CommandResponse:
        """status: the latest actuation status, to say at once if the mode is unavailable and why."""
        request = actuation_pb2.ModeRequest(mode=MODES[body.mode], requested_by=who.name, reason=body.reason)
        self._run_on_worker(lambda: publish("gateway/mode_request", request))
        detail = f"mode {body.mode.value} requested"
        for availability in status.availability if status is not None else []:
            if availability.mode == request.mode and not availability.available:
                detail += f"; currently unavailable: {availability.unmet_condition}"
        return self.record(Command.MODE, who, body.reason, CommandOutcome.SENT, detail)

    def estop(self, who: Principal, body: EstopCommand, publish: Callable[[str, object], None]) -> CommandResponse:
        stop = actuation_pb2.EmergencyStop(requested_by=who.name, reason=body.reason)
        self._run_on_worker(lambda: publish("gateway/estop", stop))
        return self.record(Command.ESTOP, who, body.reason, CommandOutcome.SENT, "emergency stop sent")

    def planner_force(self, who: Principal, body: PlannerForceCommand, publish: Callable[[str, object], None],
                      message_type: type | None) -> CommandResponse:
        """message_type: what the planner_force topic carries; None while the bus has no such topic."""
        if message_type is None:
            return self.record(Command.PLANNER_FORCE, who, body.reason, CommandOutcome.REFUSED,
                               f"the bus has no {PLANNER_FORCE_TOPIC} topic: the planner cannot be forced")
        force = message_type(state=body.state, requested_by=who.name, reason=body.reason)
        self._run_on_worker(lambda: publish(PLANNER_FORCE_TOPIC, force))
        return self.record(Command.PLANNER_FORCE, who, body.reason, CommandOutcome.SENT,
                           f"planner forced to {body.state} requested")
