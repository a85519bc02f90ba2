"""Gateway service: serves the vehicle's health and live state over HTTP (FastAPI on uvicorn).

Bus handlers run on the service's worker thread and only write to the StateStore; the HTTP
server runs on its own thread and only reads it. Neither waits for the other, so a stuck or
failed HTTP server never holds up the bus side, and the stack never waits for the gateway.
"""

from __future__ import annotations

import time
from collections import defaultdict

from coopdrive.bus import TOPICS, Envelope
from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.service import Service
from coopdrive.services.gateway.api import build_app
from coopdrive.services.gateway.config import GatewayConfig
from coopdrive.services.gateway.models import HealthResponse, StateResponse
from coopdrive.services.gateway.reports import health_report, service_participant, state_report
from coopdrive.services.gateway.server import HttpServerThread
from coopdrive.services.gateway.state_store import StateStore

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
        for service, topics in self.topics.items():
            for topic in topics:
                source = WORLD_ID if topic in WORLD_TOPICS else self.vehicle_id
                self.ctx.subscribe(topic, self._recorder(service), vehicle_id=source)
        self.ctx.watch_liveliness(self.on_liveliness)
        self.ctx.every(CLOCK_TICK_S, self.on_tick)
        token = config.read_token.get_secret_value() if config.read_token and not config.readonly_open else None
        self.server = HttpServerThread(build_app(self.health, self.state, token), config.host, config.port)
        try:
            self.server.start()
        except OSError as error:
            self.count("http_start_failures")
            self.ctx.log.error("gateway cannot listen on %s:%d: %s", config.host, config.port, error)
            self.ctx.request_stop(f"cannot listen on {config.host}:{config.port}: {error}")
            return
        self.ctx.log.info("gateway for %s on http://%s:%d", self.vehicle_id, config.host, config.port)

    def stop(self) -> None:
        server = getattr(self, "server", None)
        if server is not None and not server.stop(self.config.shutdown_timeout_s):
            self.ctx.log.warning("gateway HTTP server did not stop within %.1f s; abandoning its thread",
                                 self.config.shutdown_timeout_s)

    # ----- bus side (worker thread) ---------------------------------------------------------
    def _recorder(self, service: str):
        def record(envelope: Envelope) -> None:
            self.store.note_clock(self.ctx.now_s())
            self.store.record(service, envelope.topic, envelope.message, envelope.message.header.sent_time_s,
                              time.monotonic())
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

    # ----- HTTP side (server threads) -------------------------------------------------------
    def health(self) -> HealthResponse:
        config: GatewayConfig = self.config
        return health_report(self.store.snapshot(time.monotonic()), self.vehicle_id, self.topics,
                             config.required_services, config.silent_after_s)

    def state(self) -> StateResponse:
        return state_report(self.store.snapshot(time.monotonic()), self.vehicle_id)
