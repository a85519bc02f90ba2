"""Services run as processes with their generated credentials do on the secured bus what the runtime does for them
(liveliness token, info queryable, diagnostics) and what their declarations say, all within their access rules."""

import queue

import httpx

from coopdrive.bus import Bus, BusConfig, KeyLayout
from coopdrive.launch.ports import free_tcp_port
from coopdrive.v1 import diagnostics_pb2
from tests.bus.secure_bus import DEADLINE_S, OBSERVER, VEHICLE, client_config, wait_until


def test_a_service_with_its_credentials_shows_its_token_answers_its_info_and_reports_its_authenticated_session(
        credentials, router_log, spawn):
    layout = KeyLayout()
    spawn("service", "control", "--vehicle", VEHICLE, "--zenoh-config", client_config(credentials, "control"),
          "--set", "period_s=0.05")
    observer = Bus(BusConfig(zenoh_config_file=client_config(credentials, OBSERVER)))
    reports: queue.Queue = queue.Queue()
    try:
        observer.subscribe(VEHICLE, "diagnostics/control", reports.put)
        token = layout.liveliness(VEHICLE, "control")
        wait_until(lambda: token in observer.alive_tokens(layout.liveliness(VEHICLE, "*")),
                   "the observer saw control's liveliness token")
        [info] = observer.query(layout.service_info(VEHICLE, "control"), diagnostics_pb2.ServiceInfo)
        assert (info.service, info.vehicle_id, info.state) == ("control", VEHICLE, "running")
        report = reports.get(timeout=DEADLINE_S).message
        assert report.header.sender == "control"
        assert (report.message, report.counters["bus_authenticated"]) == ("bus mtls", 1.0)
        assert observer.mode == "mtls"
    finally:
        observer.close()


def test_a_planner_process_with_its_credentials_reaches_control_through_the_router(credentials, router_log, spawn):
    spawn("service", "planner", "--vehicle", VEHICLE, "--zenoh-config", client_config(credentials, "planner"))
    control = Bus(BusConfig(zenoh_config_file=client_config(credentials, "control")))
    behaviours: queue.Queue = queue.Queue()
    try:
        control.subscribe(VEHICLE, "planner/behaviour", behaviours.put)
        behaviour = behaviours.get(timeout=DEADLINE_S)
        assert behaviour.message.header.sender == "planner" and behaviour.message.desired_speed_mps == 25.0
    finally:
        control.close()


def test_the_gateway_with_its_credentials_shows_the_bus_mode_mtls_on_health(credentials, router_log, spawn):
    port = free_tcp_port()
    gateway = spawn("service", "gateway", "--vehicle", VEHICLE, "--zenoh-config", client_config(credentials, "gateway"),
                    "--set", "host=127.0.0.1", "--set", f"port={port}")
    health: dict = {}

    def answered() -> bool:
        try:
            health.update(httpx.get(f"http://127.0.0.1:{port}/health", timeout=5.0).json())
        except httpx.TransportError:
            assert gateway.poll() is None, gateway.stderr.read()
            return False
        return True

    wait_until(answered, "the gateway answered /health")
    assert health["bus_mode"] == "mtls"
