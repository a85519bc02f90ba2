"""GatewayService wiring with an in-memory context (no Zenoh): what it subscribes to, and what it then serves."""

import httpx
import pytest

from coopdrive.launch.ports import free_tcp_port
from coopdrive.runtime.registry import VEHICLE_STACK
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.gateway.service import GatewayService
from coopdrive.v1 import ego_pb2, sim_pb2, v2x_pb2

REQUEST_TIMEOUT_S = 20.0


@pytest.fixture
def gateway():
    ctx = MemoryContext()
    port = free_tcp_port()
    service = GatewayService(GatewayService.Config(port=port), ctx)
    service.start()
    with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=REQUEST_TIMEOUT_S) as client:
        yield ctx, client
    service.stop()


def test_it_subscribes_to_the_world_clock_and_to_the_vehicle_s_topics_but_not_its_own(gateway):
    ctx, _ = gateway
    assert ("world", "clock") in ctx.subscriptions()
    assert ("ego", "can/vehicle") in ctx.subscriptions()
    assert ("ego", "ego/state") in ctx.subscriptions()
    assert not any(topic.startswith("gateway/") for _, topic in ctx.subscriptions())


def test_liveliness_of_the_vehicle_s_services_and_the_world_simulator_shows_in_health(gateway):
    ctx, client = gateway
    for participant in ["world/sim", *(f"ego/{name}" for name in VEHICLE_STACK), "leader/planner"]:
        ctx.set_alive(participant, True)
    ctx.set_alive("ego/scene", False)
    ctx.set_alive("leader/v2x", True)  # another vehicle's service is not ours
    ctx.set_alive("ego/v2x", False)
    services = client.get("/health").json()["services"]
    assert services["sim"]["alive"] and services["planner"]["alive"]
    assert not services["scene"]["alive"]
    assert not services["v2x"]["alive"]


def test_a_message_on_the_bus_shows_in_state_with_its_age_on_the_vehicle_clock(gateway):
    ctx, client = gateway
    ego = ego_pb2.EgoState(speed_mps=17.0)
    ego.header.sent_time_s = 5.0
    ctx.clock.set(5.25)
    ctx.deliver("ego/state", ego)
    state = client.get("/state").json()
    assert state["ego_state"]["message"]["speed_mps"] == 17.0
    assert state["ego_state"]["age_s"] == pytest.approx(0.25)
    assert state["clock_s"] == pytest.approx(5.25)


def test_the_clock_tick_moves_the_gateway_s_clock_between_messages(gateway):
    ctx, client = gateway
    ctx.deliver("clock", sim_pb2.SimClock(time_s=1.0), vehicle_id="world")
    ctx.advance_to(7.5)
    assert client.get("/health").json()["clock_s"] == 7.5


def test_a_gateway_that_cannot_listen_asks_its_service_to_stop_instead_of_crashing():
    ctx = MemoryContext()
    first = GatewayService(GatewayService.Config(port=free_tcp_port()), ctx)
    first.start()
    try:
        second_ctx = MemoryContext()
        second = GatewayService(GatewayService.Config(port=first.config.port), second_ctx)
        second.start()
        second.stop()
        assert "cannot listen" in second_ctx.stop_reasons[0]
        assert second.counters["http_start_failures"] == 1
    finally:
        first.stop()


def test_health_shows_each_v2x_station_s_reception_ratio_at_its_own_expected_rate(gateway):
    """Issue 77: a standard station at 10 Hz and a GCDC one at 25 Hz, each judged at its own rate."""
    ctx, client = gateway
    status = v2x_pb2.V2xStatus()
    status.stations.add(station_id=4242, state=v2x_pb2.LINK_STATE_ACTIVE, reception_ratio=0.97,
                        expected_cam_rate_hz=10.0)
    status.stations.add(station_id=7, state=v2x_pb2.LINK_STATE_LOST, reception_ratio=0.2, expected_cam_rate_hz=25.0)
    ctx.deliver("v2x/status", status)
    stations = {s["station_id"]: s for s in client.get("/health").json()["v2x_stations"]}
    assert stations[4242] == {"station_id": 4242, "active": True, "reception_ratio": pytest.approx(0.97),
                              "expected_cam_rate_hz": 10.0}
    assert not stations[7]["active"] and stations[7]["expected_cam_rate_hz"] == 25.0
