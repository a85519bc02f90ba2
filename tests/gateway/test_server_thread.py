"""HttpServerThread and GatewayConfig: the server starts on its thread, stops promptly, reports a taken port."""

import socket

import httpx
import pytest
from ping_app import ping_app
from pydantic import ValidationError

from coopdrive.launch.ports import free_tcp_port
from coopdrive.services.gateway.config import GatewayConfig
from coopdrive.services.gateway.server import HttpServerThread

# Generous: a loaded 2-core machine may take a while to schedule the server thread.
START_DEADLINE_S = 20.0
STOP_TIMEOUT_S = 5.0


def test_the_server_answers_on_its_port_and_stops_when_asked():
    port = free_tcp_port()
    server = HttpServerThread(ping_app(), "127.0.0.1", port)
    server.start()
    try:
        response = httpx.get(f"http://127.0.0.1:{port}/ping", timeout=START_DEADLINE_S)
        assert response.json() == {"pong": True}
    finally:
        assert server.stop(STOP_TIMEOUT_S)
    assert not server.running
    assert not server.failed
    with pytest.raises(httpx.ConnectError):
        httpx.get(f"http://127.0.0.1:{port}/ping", timeout=1.0)


def test_a_port_already_taken_is_reported_by_start():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen(1)
        server = HttpServerThread(ping_app(), "127.0.0.1", holder.getsockname()[1])
        with pytest.raises(OSError):
            server.start()
    assert server.stop(STOP_TIMEOUT_S)


def test_the_gateway_listens_on_loopback_with_open_read_endpoints_by_default():
    config = GatewayConfig(port=8123)
    assert config.host == "127.0.0.1"
    assert config.readonly_open
    assert config.vehicle_id is None


def test_closing_the_read_endpoints_without_a_token_is_a_config_error():
    with pytest.raises(ValidationError, match="read_token"):
        GatewayConfig(port=8123, readonly_open=False)


def test_an_unknown_config_key_is_an_error():
    with pytest.raises(ValidationError):
        GatewayConfig(port=8123, prot=1)
