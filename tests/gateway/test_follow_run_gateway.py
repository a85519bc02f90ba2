"""Over real HTTP: `coopdrive run follow --realtime --gateway PORT` serves the live stack, and stops on SIGTERM.

The tests that only watch share the file's run (conftest.follow_run); the one that stops a run starts its own.
Deadlines for polling are generous (a loaded 2-core machine starts the run's processes); the only timed
assertion is the issue's: the run exits within 3 s of SIGTERM.
"""

import signal

import httpx
import pytest

from coopdrive.runtime.registry import VEHICLE_STACK

pytestmark = pytest.mark.whole_run

STARTUP_DEADLINE_S = 90.0
DATA_DEADLINE_S = 60.0
SHUTDOWN_LIMIT_S = 3.0


@pytest.fixture(scope="module")
def run(follow_run):
    return follow_run


def stack_alive(health: dict) -> bool:
    return all(health["services"].get(name, {}).get("alive") for name in VEHICLE_STACK)


def test_health_reports_every_stack_service_alive_under_its_participant_name(run):
    health = run.poll_json("/health", stack_alive, STARTUP_DEADLINE_S, "live stack in /health")
    for name in VEHICLE_STACK:
        assert health["services"][name]["participant"] == f"ego/{name}"
        assert health["services"][name]["topics"]
    assert health["services"]["sim"]["participant"] == "world/sim"
    assert health["vehicle_id"] == "ego"


def test_health_becomes_ok_with_every_required_service_publishing(run):
    def publishing(health: dict) -> bool:
        return health["status"] == "ok"

    health = run.poll_json("/health", publishing, DATA_DEADLINE_S, "status ok in /health")
    # follow is a scenario file like the others: its stack runs v2x too
    for name in ("sim", *VEHICLE_STACK, "v2x"):
        service = health["services"][name]
        assert service["alive"] and service["message_rate_hz"] > 0
        assert service["last_message_age_s"] is not None and service["last_message_age_s"] >= 0
    assert health["clock_s"] > 0


def test_state_carries_a_moving_ego_and_a_forward_mio(run):
    def following(state: dict) -> bool:
        ego, scene = state.get("ego_state"), state.get("scene")
        return (ego is not None and ego["message"]["speed_mps"] > 0
                and scene is not None and scene["message"]["has_forward_mio"])

    state = run.poll_json("/state", following, DATA_DEADLINE_S, "moving ego with a forward MIO in /state")
    assert state["ego_state"]["type_name"] == "coopdrive.v1.EgoState"
    assert state["scene"]["message"]["forward_mio_id"] > 0
    for field in ("planner_state", "control_command", "actuation_status"):
        assert state[field] is not None, field


def test_the_openapi_document_lists_the_read_endpoints(run):
    document = run.http.get("/openapi.json").json()
    assert {"/health", "/state"} <= set(document["paths"])


def test_the_run_with_its_gateway_exits_within_3_s_of_sigterm(own_follow_run):
    own_follow_run.poll_json("/health", stack_alive, STARTUP_DEADLINE_S, "live stack in /health")
    own_follow_run.process.send_signal(signal.SIGTERM)
    own_follow_run.process.wait(timeout=SHUTDOWN_LIMIT_S)
    with pytest.raises(httpx.TransportError):
        own_follow_run.http.get("/health")
