"""The read endpoints over real HTTP: each answers its documented model, and closed ones need a token."""

import pytest

from conftest import OBSERVER_TOKEN, OPERATOR_TOKEN, TOKENS
from coopdrive.services.gateway.models import HealthResponse, StateResponse
from coopdrive.services.gateway.view_models import PlannerResponse, SceneResponse, V2xStationsResponse

READ_ENDPOINTS = {"/health": HealthResponse, "/state": StateResponse, "/v2x/stations": V2xStationsResponse,
                  "/scene": SceneResponse, "/planner": PlannerResponse}


@pytest.fixture
def gateway(make_gateway, feed):
    gateway = make_gateway()
    feed(gateway.ctx)
    return gateway


def test_every_read_endpoint_answers_its_model_without_credentials_by_default(gateway):
    for path, model in READ_ENDPOINTS.items():
        response = gateway.http.get(path)
        assert response.status_code == 200, path
        model.model_validate(response.json())


def test_the_stations_carry_link_statistics_and_trust_from_the_v2x_status(gateway):
    stations = gateway.http.get("/v2x/stations").json()
    by_id = {s["station_id"]: s for s in stations["stations"]}
    assert by_id[4242]["state"] == "active" and by_id[4242]["trust"] == 0.9 and by_id[4242]["verified"]
    assert by_id[4242]["reception_ratio"] == 0.98 and by_id[4242]["message_rate_hz"] == 25.0
    assert by_id[4242]["expected_cam_rate_hz"] == 25.0
    assert by_id[99]["state"] == "lost"
    assert (stations["active_count"], stations["lost_count"]) == (1, 2)
    assert stations["rejected_by_reason"] == {"implausible_speed": 3}


def test_each_station_shows_whether_it_signs_and_how_its_signatures_and_signer_checked_out(gateway):
    by_id = {s["station_id"]: s for s in gateway.http.get("/v2x/stations").json()["stations"]}
    heard, refused = by_id[4242], by_id[666]
    assert (heard["signed"], heard["verified"], heard["trusted"]) == (True, True, True)
    assert (heard["messages_signed"], heard["messages_verified"], heard["messages_trusted"],
            heard["signature_failures"]) == (250, 249, 249, 1)
    assert (refused["signed"], refused["verified"], refused["trusted"]) == (True, False, False)
    assert (refused["messages_refused_by_security"], refused["messages_untrusted"]) == (12, 12)
    assert refused["last_security_reason"] == "untrusted"
    # the trust is the scene's, which knows the station's packets fail security
    assert refused["trust"] == 0.05


def test_scene_objects_carry_each_property_s_confidence_and_unknown_ones_as_null(gateway):
    scene = gateway.http.get("/scene").json()
    lead = scene["objects"][0]
    assert lead["object_class"] == "car" and lead["is_forward_mio"]
    assert lead["position"]["confidence"] == 0.8 and lead["position"]["sources"] == ["radar", "v2v"]
    assert lead["speed_mps"] == {"value": 14.0, "confidence": 0.7, "sources": []}
    assert lead["accel_mps2"]["value"] is None and lead["accel_mps2"]["confidence"] is None
    assert scene["forward_mio_id"] == 7


def test_the_planner_view_has_the_machine_its_graph_and_recent_transitions(gateway):
    planner = gateway.http.get("/planner").json()
    assert (planner["scenario"], planner["machine"], planner["state"]) == ("platoon", "platooning", "FOLLOWING")
    assert planner["graph_mermaid"].startswith("stateDiagram-v2")
    assert planner["recent_transitions"][0]["reason"] == "gap reached"


def test_the_planner_graph_stays_known_when_later_states_are_sent_without_it(gateway):
    from coopdrive.v1 import planner_pb2
    gateway.ctx.deliver("planner/state", planner_pb2.PlannerState(machine="platooning", state="LEAVING"))
    planner = gateway.http.get("/planner").json()
    assert planner["state"] == "LEAVING" and "JOINING --> FOLLOWING" in planner["graph_mermaid"]


def test_the_openapi_document_names_the_model_of_every_endpoint(gateway):
    document = gateway.http.get("/openapi.json").json()
    for path, model in READ_ENDPOINTS.items():
        schema = document["paths"][path]["get"]["responses"]["200"]["content"]["application/json"]["schema"]
        assert schema["$ref"].endswith(f"/{model.__name__}")
    assert {"/mode", "/estop", "/planner/force", "/recording", "/metrics"} <= set(document["paths"])
    assert {"StationView", "SceneObjectView", "PropertyView", "TransitionView", "ModeCommand"} <= set(
        document["components"]["schemas"])


def test_the_hmi_and_the_interactive_docs_are_served(gateway):
    page = gateway.http.get("/")
    assert page.status_code == 200 and "birdseye" in page.text
    assert gateway.http.get("/hmi.js").status_code == 200
    assert gateway.http.get("/docs").status_code == 200


def test_closed_read_endpoints_refuse_a_request_without_a_known_token(make_gateway):
    gateway = make_gateway(readonly_open=False, tokens=TOKENS)
    for path in [*READ_ENDPOINTS, "/metrics", "/commands"]:
        assert gateway.http.get(path).status_code == 401, path
        assert gateway.http.get(path, headers={"Authorization": "Bearer wrong"}).status_code == 401, path


def test_closed_read_endpoints_answer_any_configured_token(make_gateway):
    gateway = make_gateway(readonly_open=False, tokens=TOKENS, read_token="legacy-read")
    for token in (OBSERVER_TOKEN, OPERATOR_TOKEN, "legacy-read"):
        assert gateway.http.get("/scene", headers={"Authorization": f"Bearer {token}"}).status_code == 200, token
