"""Actuation service: the only door to the vehicle. Feeds the Actuator and sends its ACT_ frames every cycle.

Data handlers feed the Actuator (commands, vehicle state, ego state, V2X health, mode requests, liveliness); the
50 Hz cycle steps it and publishes the ACT_ frames that are due (each at its DBC cycle time, or at once when it
changes) on can/command, the ActuatorCommand on actuation/command and any driver override; the status goes out
at 10 Hz.
"""

from __future__ import annotations

from coopdrive.bus import Envelope
from coopdrive.can.bus_input import VehicleBusInput
from coopdrive.can.bus_reader import VehicleBusReader
from coopdrive.can.wire import to_protobuf
from coopdrive.runtime.service import Service
from coopdrive.services.actuation.actuator import Actuator
from coopdrive.services.actuation.config import ActuationServiceConfig, EngageMode
from coopdrive.v1 import actuation_pb2, v2x_pb2, vehicle_pb2

ENGAGE_REQUESTER = "engage_on_start"
ENGAGE_MODES = {EngageMode.COOPERATIVE: actuation_pb2.DRIVING_MODE_COOPERATIVE,
                EngageMode.AUTONOMOUS: actuation_pb2.DRIVING_MODE_AUTONOMOUS}


def v2x_healthy(status: v2x_pb2.V2xStatus) -> bool:
    """Cooperative driving needs someone to cooperate with: healthy while at least one station is heard."""
    return any(station.state == v2x_pb2.LINK_STATE_ACTIVE for station in status.stations)


class ActuationService(Service):
    name = "actuation"
    Config = ActuationServiceConfig

    def start(self) -> None:
        c: ActuationServiceConfig = self.config
        self.actuator = Actuator(c.actuator_config(self.ctx.vehicle_id))
        self.engage_pending = ENGAGE_MODES.get(c.engage_on_start)
        self.last_refusal = ""
        self.status: actuation_pb2.ActuationStatus | None = None
        self.ctx.subscribe("control/command", self.on_control_command)
        self.ctx.subscribe("ego/state", self.on_ego_state)
        if c.require_v2x:
            self.ctx.subscribe("v2x/status", self.on_v2x_status)
        self.ctx.subscribe("gateway/mode_request", self.on_mode_request)
        self.ctx.subscribe("gateway/estop", self.on_estop)
        self.ctx.watch_liveliness(self.on_liveliness)
        self.ctx.every(1.0 / c.rate_hz, self.actuate)
        self.ctx.every(1.0 / c.status_rate_hz, self.publish_status)
        reader = VehicleBusReader(on_vehicle_state=self.on_vehicle_state, vehicle_can=c.vehicle_can)
        self.vehicle_bus = VehicleBusInput(self.ctx, reader, c.can_port, owns_bus=True)

    def stop(self) -> None:
        if getattr(self, "vehicle_bus", None) is not None:  # not there when start failed to open the interface
            self.vehicle_bus.close()

    # ----- inputs ---------------------------------------------------------------------------
    def on_control_command(self, envelope: Envelope) -> None:
        if not self.actuator.on_control_command(envelope.message, self.ctx.now_s()):
            self.count("rejected_commands")

    def on_vehicle_state(self, state: vehicle_pb2.VehicleCanState) -> None:
        if self.actuator.on_vehicle_state(state, self.ctx.now_s()) is not None:
            self.count("driver_overrides")

    def on_ego_state(self, envelope: Envelope) -> None:
        self.actuator.on_ego_state(envelope.message, self.ctx.now_s())

    def on_v2x_status(self, envelope: Envelope) -> None:
        self.actuator.on_v2x_health(v2x_healthy(envelope.message), self.ctx.now_s())

    def on_mode_request(self, envelope: Envelope) -> None:
        request = envelope.message
        decision = self.actuator.on_mode_request(request, self.ctx.now_s())
        if not decision.accepted:
            self.count("mode_requests_refused")
            self.ctx.log.info("refused %s from %s: %s", actuation_pb2.DrivingMode.Name(request.mode),
                              request.requested_by or "unspecified", decision.unmet)

    def on_estop(self, envelope: Envelope) -> None:
        self.actuator.on_estop(self.ctx.now_s(), envelope.message.requested_by)
        self.count("emergency_stops")

    def on_liveliness(self, participant: str, alive: bool) -> None:
        vehicle_id, _, service = participant.partition("/")
        if vehicle_id == self.ctx.vehicle_id:
            self.actuator.on_service_liveness(service, alive)

    # ----- time triggers --------------------------------------------------------------------
    def actuate(self, now_s: float) -> None:
        if self.engage_pending is not None:
            self._engage(now_s)
        frames, self.status = self.actuator.step(now_s)
        for frame in frames:
            self.ctx.publish("can/command", to_protobuf(frame), sample_time_s=now_s)
        self.vehicle_bus.send(frames)
        self.counters.update(self.vehicle_bus.counts())
        command = self.actuator.actuator_command(now_s)
        if command is not None:
            self.ctx.publish("actuation/command", command, sample_time_s=now_s)
        for event in self.actuator.take_override_events():
            self.ctx.publish("actuation/override", event, sample_time_s=event.header.sample_time_s)
        self.counters["frames_sent"] = self.actuator.frames_sent
        self.counters["frames_rejected"] = self.actuator.frames_rejected

    def _engage(self, now_s: float) -> None:
        request = actuation_pb2.ModeRequest(mode=self.engage_pending, requested_by=ENGAGE_REQUESTER)
        decision = self.actuator.on_mode_request(request, now_s)
        if decision.accepted:
            self.engage_pending = None
            self.ctx.log.info("engaged %s at %.2f s", actuation_pb2.DrivingMode.Name(request.mode), now_s)
            return
        self.count("engage_refused")
        refusal = str(decision.unmet)
        if refusal != self.last_refusal:
            self.last_refusal = refusal
            self.ctx.log.info("engage at start refused at %.2f s: %s", now_s, refusal)

    def publish_status(self, now_s: float) -> None:
        if self.status is not None:
            self.ctx.publish("actuation/status", self.status, sample_time_s=self.status.header.sample_time_s)
