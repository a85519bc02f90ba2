"""Planner service: decides the behaviour (speed, spacing, whom to follow)."""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.v1 import planner_pb2


class PlannerConfig(ServiceConfig):
    rate_hz: float = 10.0
    desired_speed_mps: float = 25.0
    standstill_m: float = 6.0
    time_gap_s: float = 1.5


class PlannerService(Service):
    name = "planner"
    Config = PlannerConfig

    def start(self) -> None:
        self.scene = None
        self.state = "cruise"
        self.state_since_s = 0.0
        self.transitions: list[planner_pb2.StateTransition] = []
        self.ctx.subscribe("scene", self.on_scene)
        self.ctx.every(1.0 / self.config.rate_hz, self.plan)

    def on_scene(self, envelope: Envelope) -> None:
        self.scene = envelope.message

    def plan(self, now_s: float) -> None:
        c: PlannerConfig = self.config
        request = planner_pb2.BehaviourRequest(desired_speed_mps=c.desired_speed_mps)
        request.spacing.standstill_m = c.standstill_m
        request.spacing.time_gap_s = c.time_gap_s
        following = self.scene is not None and self.scene.has_forward_mio
        if following:
            request.targets.add(object_id=self.scene.forward_mio_id, role=planner_pb2.TARGET_ROLE_PREDECESSOR)
        self._enter("follow" if following else "cruise", now_s)
        self.ctx.publish("planner/behaviour", request)
        state = planner_pb2.PlannerState(scenario=planner_pb2.SCENARIO_FOLLOW, machine="follow", state=self.state,
                                         time_in_state_s=now_s - self.state_since_s,
                                         recent_transitions=self.transitions[-10:])
        self.ctx.publish("planner/state", state)

    def _enter(self, state: str, now_s: float) -> None:
        if state == self.state:
            return
        self.transitions.append(planner_pb2.StateTransition(time_s=now_s, from_state=self.state, to_state=state,
                                                            event="forward_mio_changed"))
        self.state, self.state_since_s = state, now_s
