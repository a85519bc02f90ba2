"""The HTTP API on a loopback port, fed by fixed responses: routes, models in the OpenAPI document, read token."""

import httpx
import pytest

from coopdrive.launch.ports import free_tcp_port
from coopdrive.services.gateway.api import build_app
from coopdrive.services.gateway.models import HealthResponse, HealthStatus, StateResponse
from coopdrive.services.gateway.server import HttpServerThread

# Generous: a loaded machine may be slow to schedule the server thread.
REQUEST_TIMEOUT_S = 20.0
STOP_TIMEOUT_S = 5.0


def health() -> HealthResponse:
    return HealthResponse(status=HealthStatus.OK, vehicle_id="ego", clock_s=1.0, services={})


def state() -> StateResponse:
    return StateResponse(vehicle_id="ego", clock_s=1.0, ego_state=None, scene=None, planner_state=None,
                         control_command=None, actuation_status=None)


def serve(read_token: str | None = None):
    port = free_tcp_port()
    server = HttpServerThread(build_app(health, state, read_token), "127.0.0.1", port)
    server.start()
    with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=REQUEST_TIMEOUT_S) as client:
        yield client
    server.stop(STOP_TIMEOUT_S)


@pytest.fixture
def client():
    yield from serve()


@pytest.fixture
def closed_client():
    yield from serve(read_token="s3cret")


def test_health_and_state_answer_without_credentials_by_default(client):
    assert client.get("/health").json()["status"] == "ok"
    assert client.get("/state").json()["vehicle_id"] == "ego"


def test_the_openapi_document_names_the_response_models_of_every_path(client):
    document = client.get("/openapi.json").json()
    assert {"/health", "/state"} <= set(document["paths"])
    schemas = document["components"]["schemas"]
    assert {"HealthResponse", "ServiceHealth", "StateResponse", "MessageEntry", "HealthStatus"} <= set(schemas)
    health_schema = document["paths"]["/health"]["get"]["responses"]["200"]["content"]["application/json"]["schema"]
    assert health_schema["$ref"].endswith("/HealthResponse")


def test_closed_read_endpoints_refuse_a_request_without_the_token(closed_client):
    assert closed_client.get("/health").status_code == 401
    assert closed_client.get("/state", headers={"Authorization": "Bearer wrong"}).status_code == 401


def test_closed_read_endpoints_answer_with_the_token(closed_client):
    assert closed_client.get("/health", headers={"Authorization": "Bearer s3cret"}).status_code == 200


def test_the_interactive_docs_are_served(client):
    assert client.get("/docs").status_code == 200
