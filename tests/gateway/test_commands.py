"""Commands over real HTTP: 401 without a known token, 403 for a role that may not, 202 and a bus message otherwise."""

import pytest

from conftest import OBSERVER_TOKEN, OPERATOR_TOKEN, TOKENS
from coopdrive.bus import TOPICS
from coopdrive.recording.reader import read_messages
from coopdrive.v1 import actuation_pb2

OPERATOR = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
OBSERVER = {"Authorization": f"Bearer {OBSERVER_TOKEN}"}
COMMANDS = {"/mode": {"mode": "cooperative", "reason": "test drive"},
            "/estop": {"reason": "pedestrian on track"},
            "/planner/force": {"state": "LEAVING", "reason": "end of test"},
            "/recording": {"action": "start", "reason": "log the merge"}}


@pytest.fixture
def gateway(make_gateway, tmp_path):
    return make_gateway(tokens=TOKENS, recording_dir=tmp_path / "recordings")


def test_every_command_without_a_token_is_401_and_publishes_nothing(gateway):
    for path, body in COMMANDS.items():
        response = gateway.http.post(path, json=body)
        assert response.status_code == 401, path
        assert response.headers["www-authenticate"] == "Bearer"
        assert gateway.http.post(path, json=body, headers={"Authorization": "Bearer nope"}).status_code == 401
    assert gateway.ctx.published == []


def test_every_command_from_an_observer_is_403_and_publishes_nothing(gateway):
    for path, body in COMMANDS.items():
        response = gateway.http.post(path, json=body, headers=OBSERVER)
        assert response.status_code == 403, path
        assert "dashboard (observer) may not" in response.json()["detail"]
    assert gateway.ctx.published == []


def test_a_mode_request_from_an_operator_is_published_with_who_and_why(gateway):
    response = gateway.http.post("/mode", json=COMMANDS["/mode"], headers=OPERATOR)
    assert response.status_code == 202
    assert response.json() == {"command": "mode", "outcome": "sent", "requested_by": "alice", "reason": "test drive",
                               "detail": "mode cooperative requested"}
    [(topic, request)] = gateway.ctx.published
    assert topic == "gateway/mode_request"
    assert (request.mode, request.requested_by, request.reason) == (
        actuation_pb2.DRIVING_MODE_COOPERATIVE, "alice", "test drive")


def test_a_mode_request_says_at_once_why_the_mode_is_unavailable_now(gateway, feed):
    feed(gateway.ctx)  # actuation status: cooperative unavailable, "slow enough to engage"
    response = gateway.http.post("/mode", json=COMMANDS["/mode"], headers=OPERATOR)
    assert response.status_code == 202
    assert response.json()["detail"] == "mode cooperative requested; currently unavailable: slow enough to engage"


def test_an_emergency_stop_from_an_operator_is_published_on_gateway_estop(gateway):
    assert gateway.http.post("/estop", json=COMMANDS["/estop"], headers=OPERATOR).status_code == 202
    [(topic, stop)] = gateway.ctx.published
    assert (topic, stop.requested_by, stop.reason) == ("gateway/estop", "alice", "pedestrian on track")


def test_a_command_without_a_reason_or_with_an_unknown_mode_is_422(gateway):
    assert gateway.http.post("/mode", json={"mode": "cooperative"}, headers=OPERATOR).status_code == 422
    assert gateway.http.post("/mode", json={"mode": "cooperative", "reason": ""}, headers=OPERATOR).status_code == 422
    assert gateway.http.post("/mode", json={"mode": "warp", "reason": "x"}, headers=OPERATOR).status_code == 422
    assert gateway.ctx.published == []


def test_forcing_the_planner_is_refused_with_409_while_the_bus_has_no_topic_for_it(gateway, monkeypatch):
    monkeypatch.delitem(TOPICS, "gateway/planner_force", raising=False)
    response = gateway.http.post("/planner/force", json=COMMANDS["/planner/force"], headers=OPERATOR)
    assert response.status_code == 409
    assert response.json()["outcome"] == "refused" and "gateway/planner_force" in response.json()["detail"]
    assert gateway.ctx.published == []


@pytest.mark.skipif("gateway/planner_force" not in TOPICS, reason="the bus has no planner force topic")
def test_forcing_the_planner_publishes_the_state_with_who_and_why(gateway):
    assert gateway.http.post("/planner/force", json=COMMANDS["/planner/force"], headers=OPERATOR).status_code == 202
    [(topic, force)] = gateway.ctx.published
    assert (topic, force.state, force.requested_by, force.reason) == (
        "gateway/planner_force", "LEAVING", "alice", "end of test")


def test_recording_writes_what_the_gateway_hears_to_mcap_until_stopped(gateway, feed, tmp_path):
    assert gateway.http.post("/recording", json=COMMANDS["/recording"], headers=OPERATOR).status_code == 202
    feed(gateway.ctx)
    stop = {"action": "stop", "reason": "done"}
    assert gateway.http.post("/recording", json=stop, headers=OPERATOR).json()["outcome"] == "done"
    [path] = (tmp_path / "recordings").glob("ego-*.mcap")
    topics = {recorded.topic for recorded in read_messages(path)}
    assert {"coopdrive/ego/scene", "coopdrive/ego/v2x/status"} <= topics


def test_recording_is_refused_when_no_directory_is_configured(make_gateway):
    gateway = make_gateway(tokens=TOKENS)
    response = gateway.http.post("/recording", json=COMMANDS["/recording"], headers=OPERATOR)
    assert response.status_code == 409 and "recording_dir" in response.json()["detail"]


def test_the_latest_commands_are_listed_with_who_and_why(gateway):
    gateway.http.post("/estop", json=COMMANDS["/estop"], headers=OPERATOR)
    gateway.http.post("/mode", json=COMMANDS["/mode"], headers=OPERATOR)
    listed = gateway.http.get("/commands").json()
    assert [(c["command"], c["requested_by"], c["reason"]) for c in listed] == [
        ("estop", "alice", "pedestrian on track"), ("mode", "alice", "test drive")]


def test_each_command_is_logged_with_the_token_name_and_the_reason(gateway, caplog):
    with caplog.at_level("WARNING", logger="test.gateway"):
        gateway.http.post("/mode", json=COMMANDS["/mode"], headers=OPERATOR)
        gateway.http.post("/mode", json=COMMANDS["/mode"], headers=OBSERVER)
    text = caplog.text
    assert "command mode by alice (operator): sent" in text and "reason: test drive" in text
    assert "command mode refused for dashboard: role observer may not" in text
