"""Gateway service: the vehicle's health, live state and operator commands over HTTP (FastAPI on uvicorn).

Bus handlers run on the service's worker thread and only write to the StateStore; the HTTP
server runs on its own threads and only reads it. Neither waits for the other, so a stuck or
failed HTTP server never holds up the bus side, and the stack never waits for the gateway.
Commands cross the other way through ctx.call_soon: only the worker thread publishes.
"""

from __future__ import annotations

import time
from collections import defaultdict
from datetime import datetime, timezone

from coopdrive.bus import TOPICS, Envelope
from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.service import Service
from coopdrive.services.gateway.api import build_app
from coopdrive.services.gateway.auth import Command, Principal, TokenBook
from coopdrive.services.gateway.commands import (
    PLANNER_FORCE_TOPIC,
    CommandDesk,
    CommandOutcome,
    CommandResponse,
    EstopCommand,
    ModeCommand,
    PlannerForceCommand,
    RecordingAction,
    RecordingCommand,
)
from coopdrive.services.gateway.config import GatewayConfig
from coopdrive.services.gateway.live import LiveBroadcaster
from coopdrive.services.gateway.metrics import GatewayMetrics
from coopdrive.services.gateway.models import HealthResponse, StateResponse
from coopdrive.services.gateway.recording import GatewayRecording
from coopdrive.services.gateway.reports import health_report, service_participant, state_report
from coopdrive.services.gateway.server import HttpServerThread
from coopdrive.services.gateway.state_store import StateStore
from coopdrive.services.gateway.view_models import PlannerResponse, SceneResponse, V2xStationsResponse
from coopdrive.services.gateway.views import live_frame, planner_view, scene_view, v2x_reception, v2x_view

# Simulator topics published under the world namespace rather than each vehicle's.
WORLD_TOPICS = frozenset({"clock", "ground_truth", "result"})
# Keeps the store's view of the vehicle clock current when no message arrives.
CLOCK_TICK_S = 0.1


def topics_by_service() -> dict[str, list[str]]:
    """Every publishing service (but the gateway itself) and its topics, from the topic registry."""
    topics: dict[str, list[str]] = defaultdict(list)
    for topic in TOPICS.values():
        if topic.publisher != GatewayService.name:
            topics[topic.publisher].append(topic.name)
    return dict(topics)


class GatewayService(Service):
    name = "gateway"
    Config = GatewayConfig

    def start(self) -> None:
        config: GatewayConfig = self.config
        self.vehicle_id = config.vehicle_id or self.ctx.vehicle_id
        self.topics = topics_by_service()
        self.store = StateStore(list(self.topics), config.rate_window_s)
        self.graph_mermaid: str | None = None
        self.recorder = GatewayRecording(config.recording_dir)
        self.prometheus = GatewayMetrics(self.vehicle_id)
        self.desk = CommandDesk(self.ctx.call_soon, self.ctx.log, self._count_command)
        self.live = LiveBroadcaster(self._live_frame, config.live_rate_hz, config.live_queue_frames,
                                    self.prometheus.ws_dropped.inc)
        for service, topics in self.topics.items():
            for topic in topics:
                source = WORLD_ID if topic in WORLD_TOPICS else self.vehicle_id
                self.ctx.subscribe(topic, self._recorder(service), vehicle_id=source)
        self.ctx.watch_liveliness(self.on_liveliness)
        self.ctx.every(CLOCK_TICK_S, self.on_tick)
        self.server = HttpServerThread(build_app(self, TokenBook.from_config(config)), config.host, config.port,
                                       config.tls)
        try:
            self.server.start()
        except OSError as error:
            self.count("http_start_failures")
            self.ctx.log.error("gateway cannot listen on %s:%d: %s", config.host, config.port, error)
            self.ctx.request_stop(f"cannot listen on {config.host}:{config.port}: {error}")
            return
        scheme = "https" if config.tls else "http"
        self.ctx.log.info("gateway for %s on %s://%s:%d", self.vehicle_id, scheme, config.host, config.port)

    def stop(self) -> None:
        server = getattr(self, "server", None)
        if server is not None and not server.stop(self.config.shutdown_timeout_s):
            self.ctx.log.warning("gateway HTTP server did not stop within %.1f s; abandoning its thread",
                                 self.config.shutdown_timeout_s)
        if getattr(self, "recorder", None) is not None:
            self.recorder.stop()

    # ----- bus side (worker thread) ---------------------------------------------------------
    def _recorder(self, service: str):
        def record(envelope: Envelope) -> None:
            message = envelope.message
            self.store.note_clock(self.ctx.now_s())
            self.store.record(service, envelope.topic, message, message.header.sent_time_s, time.monotonic())
            if envelope.topic == "planner/state" and message.graph_mermaid:
                self.graph_mermaid = message.graph_mermaid
            self.recorder.write(envelope.vehicle_id, envelope.topic, message)
        return record

    def on_liveliness(self, participant: str, alive: bool) -> None:
        for service in self.topics:
            if participant == service_participant(self.vehicle_id, service):
                self.store.set_alive(service, alive)

    def on_tick(self, now_s: float) -> None:
        self.store.note_clock(now_s)
        if self.server.failed:
            self.count("http_failures")
            self.ctx.request_stop(f"HTTP server failed: {self.server.error!r}")

    def _publish(self, topic: str, message) -> None:
        self.ctx.publish(topic, message)

    # ----- HTTP side (server threads) -------------------------------------------------------
    def _snapshot(self):
        return self.store.snapshot(time.monotonic())

    def health(self) -> HealthResponse:
        config: GatewayConfig = self.config
        snapshot = self._snapshot()
        return health_report(snapshot, self.vehicle_id, self.topics, config.required_services,
                             config.silent_after_s, v2x_stations=v2x_reception(snapshot), bus_mode=self.ctx.bus_mode)

    def state(self) -> StateResponse:
        return state_report(self._snapshot(), self.vehicle_id)

    def v2x_stations(self) -> V2xStationsResponse:
        return v2x_view(self._snapshot(), self.vehicle_id)

    def scene(self) -> SceneResponse:
        return scene_view(self._snapshot(), self.vehicle_id)

    def planner(self) -> PlannerResponse:
        return planner_view(self._snapshot(), self.vehicle_id, self.graph_mermaid)

    def metrics(self) -> bytes:
        self.prometheus.update(self._snapshot(), self.live.client_count)
        return self.prometheus.render()

    def _live_frame(self, seq: int) -> str:
        snapshot = self._snapshot()
        alive = {service: activity.alive for service, activity in snapshot.services.items()}
        return live_frame(snapshot, seq, alive).model_dump_json()

    def _count_command(self, command: Command, outcome: CommandOutcome) -> None:
        self.prometheus.commands.labels(command.value, outcome.value).inc()

    def recent_commands(self) -> list[CommandResponse]:
        return self.desk.recent()

    def refused(self, command: Command, who: str, detail: str) -> None:
        self.ctx.log.warning("command %s refused for %s: %s", command.value, who, detail)
        self.prometheus.commands.labels(command.value, "unauthorized").inc()

    def mode(self, who: Principal, body: ModeCommand) -> CommandResponse:
        status = self.store.latest("actuation/status")
        return self.desk.mode(who, body, self._publish, status.message if status else None)

    def estop(self, who: Principal, body: EstopCommand) -> CommandResponse:
        return self.desk.estop(who, body, self._publish)

    def planner_force(self, who: Principal, body: PlannerForceCommand) -> CommandResponse:
        topic = TOPICS.get(PLANNER_FORCE_TOPIC)
        return self.desk.planner_force(who, body, self._publish, topic.message_type if topic else None)

    def recording(self, who: Principal, body: RecordingCommand) -> CommandResponse:
        directory = self.recorder.directory
        if directory is None:
            return self.desk.record(Command.RECORDING, who, body.reason, CommandOutcome.REFUSED,
                                    "recording_dir is not configured")
        if body.action is RecordingAction.START:
            stamp = datetime.now(timezone.utc).strftime("%Y%m%dT%H%M%S%fZ")
            path = directory / f"{self.vehicle_id}-{stamp}.mcap"
            self.ctx.call_soon(lambda: self.recorder.start(path))
            return self.desk.record(Command.RECORDING, who, body.reason, CommandOutcome.DONE, f"recording to {path}")
        self.ctx.call_soon(self.recorder.stop)
        return self.desk.record(Command.RECORDING, who, body.reason, CommandOutcome.DONE, "recording stopped")
