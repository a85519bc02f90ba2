"""Planner service: feeds the scenario state machines the ego state, the scene and the V2X conversation."""

from __future__ import annotations

import math

from coopdrive.bus import Envelope
from coopdrive.runtime.service import Service
from coopdrive.services.planner.config import PlannerConfig
from coopdrive.services.planner.inputs import PlannerInputs, Received
from coopdrive.services.planner.planner import Planner, PlannerInputError
from coopdrive.v1 import planner_pb2
from coopdrive.v2x.timebase import ItsClock

V2X_TOPICS = {"v2x/iclcm": "iclcms", "v2x/cam": "cams", "v2x/denm": "denms", "v2x/mapem": "mapems",
              "v2x/spatem": "spatems"}


class PlannerService(Service):
    name = "planner"
    Config = PlannerConfig

    def start(self) -> None:
        config: PlannerConfig = self.config
        self.planner = Planner(config.logic, glosa=config.glosa, clock=ItsClock(config.clock_epoch_unix_s))
        self.inputs = PlannerInputs(station_id=config.station_id, scenario=config.scenario_value(),
                                    platoon_id=config.platoon_id, partner_station_id=config.partner_station_id)
        self.pending_force: list[planner_pb2.PlannerForce] = []
        # Per machine (the scenario's, the traffic lights'): the last transition time logged.
        self.logged_until_s: dict[str, float] = {}
        self.ctx.subscribe("ego/state", lambda envelope: setattr(self.inputs, "ego", envelope.message))
        self.ctx.subscribe("scene", lambda envelope: setattr(self.inputs, "scene", envelope.message))
        for topic, field_name in V2X_TOPICS.items():
            self.ctx.subscribe(topic, self._v2x_handler(field_name))
        self.ctx.subscribe("gateway/planner_force", lambda envelope: self.pending_force.append(envelope.message))
        self.ctx.every(1.0 / config.rate_hz, self.plan)

    def _v2x_handler(self, field_name: str):
        def store(envelope: Envelope) -> None:
            message = envelope.message
            getattr(self.inputs, field_name)[message.station_id] = Received(message, self.ctx.now_s())
        return store

    def plan(self, now_s: float) -> None:
        self._apply_forced_states(now_s)
        try:
            request, state = self.planner.step(now_s, self.inputs)
        except PlannerInputError as error:
            self.count("planner_input_errors")
            self.ctx.log.warning("planner refused its inputs: %s", error)
            return
        self.ctx.publish("planner/behaviour", request)
        self.ctx.publish("planner/state", state)
        lights = self.planner.lights_state(now_s)
        self.ctx.publish("planner/lights", lights)
        self._log_new_transitions(state)
        self._log_new_transitions(lights)

    def _log_new_transitions(self, state: planner_pb2.PlannerState) -> None:
        """Each transition once in the service log, with why it fired (a guard, a timeout, an escape)."""
        logged_until_s = self.logged_until_s.get(state.machine, -math.inf)
        for transition in state.recent_transitions:
            if transition.time_s > logged_until_s:
                self.ctx.log.info("%s: %s -> %s at %.2f s on %s: %s", state.machine, transition.from_state,
                                  transition.to_state, transition.time_s, transition.event, transition.reason)
        if state.recent_transitions:
            self.logged_until_s[state.machine] = max(logged_until_s, state.recent_transitions[-1].time_s)

    def _apply_forced_states(self, now_s: float) -> None:
        for force in self.pending_force:
            try:
                self.planner.force(force.state, now_s, who=force.requested_by, why=force.reason)
                self.count("forced_transitions")
            except (KeyError, ValueError, RuntimeError) as error:
                self.count("forced_transitions_refused")
                self.ctx.log.warning("refused to force state %r: %s", force.state, error)
        self.pending_force.clear()
