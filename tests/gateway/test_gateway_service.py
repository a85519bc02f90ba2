"""GatewayService wiring with a stand-in context (no Zenoh): what it subscribes to, and what it then serves."""

import logging

import httpx
import pytest

from coopdrive.bus import Envelope
from coopdrive.launch.ports import free_tcp_port
from coopdrive.runtime.registry import VEHICLE_STACK
from coopdrive.services.gateway.service import GatewayService
from coopdrive.v1 import ego_pb2, sim_pb2

REQUEST_TIMEOUT_S = 20.0


class FakeContext:
    vehicle_id = "ego"
    log = logging.getLogger("test.gateway")

    def __init__(self):
        self.clock_s = 0.0
        self.subscriptions: dict[tuple[str, str], object] = {}
        self.liveliness = []
        self.timers = []
        self.stop_reason = None

    def now_s(self) -> float:
        return self.clock_s

    def subscribe(self, topic, handler, vehicle_id=None):
        self.subscriptions[(vehicle_id or self.vehicle_id, topic)] = handler

    def publish(self, topic, message, sample_time_s=None):
        pass

    def every(self, period_s, handler):
        self.timers.append(handler)

    def call_soon(self, function):
        function()

    def watch_liveliness(self, handler):
        self.liveliness.append(handler)

    def request_stop(self, reason):
        self.stop_reason = reason

    def deliver(self, vehicle_id: str, topic: str, message) -> None:
        self.subscriptions[(vehicle_id, topic)](Envelope(vehicle_id, topic, message))


@pytest.fixture
def gateway():
    ctx = FakeContext()
    port = free_tcp_port()
    service = GatewayService(GatewayService.Config(port=port), ctx)
    service.start()
    with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=REQUEST_TIMEOUT_S) as client:
        yield ctx, client
    service.stop()


def test_it_subscribes_to_the_world_clock_and_to_the_vehicle_s_topics_but_not_its_own(gateway):
    ctx, _ = gateway
    assert ("world", "clock") in ctx.subscriptions
    assert ("ego", "can/vehicle") in ctx.subscriptions
    assert ("ego", "ego/state") in ctx.subscriptions
    assert not any(topic.startswith("gateway/") for _, topic in ctx.subscriptions)


def test_liveliness_of_the_vehicle_s_services_and_the_world_simulator_shows_in_health(gateway):
    ctx, client = gateway
    for participant in ["world/sim", *(f"ego/{name}" for name in VEHICLE_STACK), "leader/planner"]:
        ctx.liveliness[0](participant, True)
    ctx.liveliness[0]("ego/scene", False)
    ctx.liveliness[0]("leader/v2x", True)  # another vehicle's service is not ours
    ctx.liveliness[0]("ego/v2x", False)
    services = client.get("/health").json()["services"]
    assert services["sim"]["alive"] and services["planner"]["alive"]
    assert not services["scene"]["alive"]
    assert not services["v2x"]["alive"]


def test_a_message_on_the_bus_shows_in_state_with_its_age_on_the_vehicle_clock(gateway):
    ctx, client = gateway
    ego = ego_pb2.EgoState(speed_mps=17.0)
    ego.header.sent_time_s = 5.0
    ctx.clock_s = 5.25
    ctx.deliver("ego", "ego/state", ego)
    state = client.get("/state").json()
    assert state["ego_state"]["message"]["speed_mps"] == 17.0
    assert state["ego_state"]["age_s"] == pytest.approx(0.25)
    assert state["clock_s"] == pytest.approx(5.25)


def test_the_clock_tick_moves_the_gateway_s_clock_between_messages(gateway):
    ctx, client = gateway
    ctx.deliver("world", "clock", sim_pb2.SimClock(time_s=1.0))
    for timer in ctx.timers:
        timer(7.5)
    assert client.get("/health").json()["clock_s"] == 7.5


def test_a_gateway_that_cannot_listen_asks_its_service_to_stop_instead_of_crashing():
    ctx = FakeContext()
    first = GatewayService(GatewayService.Config(port=free_tcp_port()), ctx)
    first.start()
    try:
        second_ctx = FakeContext()
        second = GatewayService(GatewayService.Config(port=first.config.port), second_ctx)
        second.start()
        second.stop()
        assert "cannot listen" in second_ctx.stop_reason
        assert second.counters["http_start_failures"] == 1
    finally:
        first.stop()
