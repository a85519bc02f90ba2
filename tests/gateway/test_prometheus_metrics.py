"""/metrics in the Prometheus text format, read back with prometheus_client's own parser."""

import math

from prometheus_client.parser import text_string_to_metric_families

from conftest import OPERATOR_TOKEN, TOKENS


def samples(text: str) -> dict[tuple[str, tuple], float]:
    return {(s.name, tuple(sorted(s.labels.items()))): s.value
            for family in text_string_to_metric_families(text) for s in family.samples}


def test_the_metrics_parse_and_carry_speed_gap_time_gap_stations_and_rates(make_gateway, feed):
    gateway = make_gateway()
    gateway.ctx.set_alive("ego/scene", True)
    feed(gateway.ctx, speed_mps=15.0)
    response = gateway.http.get("/metrics")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/plain")
    values = samples(response.text)
    assert values[("coopdrive_ego_speed_mps", ())] == 15.0
    assert values[("coopdrive_gap_m", ())] == 30.0
    assert values[("coopdrive_time_gap_s", ())] == 2.0
    assert values[("coopdrive_v2x_stations", (("state", "active"),))] == 1
    # one gone quiet, one only ever refused by the security mode
    assert values[("coopdrive_v2x_stations", (("state", "lost"),))] == 2
    assert values[("coopdrive_service_alive", (("service", "scene"),))] == 1
    assert values[("coopdrive_service_alive", (("service", "planner"),))] == 0
    assert ("coopdrive_service_message_rate_hz", (("service", "v2x"),)) in values
    assert values[("coopdrive_scene_objects", ())] == 1


def test_unknown_values_are_nan_before_any_message(make_gateway):
    values = samples(make_gateway().http.get("/metrics").text)
    assert math.isnan(values[("coopdrive_ego_speed_mps", ())])
    assert math.isnan(values[("coopdrive_gap_m", ())])


def test_commands_are_counted_by_outcome(make_gateway):
    gateway = make_gateway(tokens=TOKENS)
    body = {"reason": "drill"}
    gateway.http.post("/estop", json=body)
    gateway.http.post("/estop", json=body, headers={"Authorization": f"Bearer {OPERATOR_TOKEN}"})
    values = samples(gateway.http.get("/metrics").text)
    assert values[("coopdrive_gateway_commands_total", (("command", "estop"), ("outcome", "sent")))] == 1
    assert values[("coopdrive_gateway_commands_total", (("command", "estop"), ("outcome", "unauthorized")))] == 1


def test_two_gateways_keep_their_metrics_apart(make_gateway, feed):
    first, second = make_gateway(), make_gateway()
    feed(first.ctx, speed_mps=20.0)
    assert samples(first.http.get("/metrics").text)[("coopdrive_ego_speed_mps", ())] == 20.0
    assert math.isnan(samples(second.http.get("/metrics").text)[("coopdrive_ego_speed_mps", ())])
