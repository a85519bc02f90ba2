"""The bus's access rules come from the services' topic declarations: what each certificate may put and subscribe
to, and the router's access control built from that."""

import importlib

import pytest

from coopdrive.bus.bus_grant import bus_grants, observer_grant, service_grant
from coopdrive.bus.router_access import access_control
from coopdrive.bus.services import service_entry
from coopdrive.bus.topic import Topic
from coopdrive.bus.topics import declarations_of, published_by
from coopdrive.v1 import diagnostics_pb2


def rule_keys(section: dict, rule_id: str) -> list[str]:
    [rule] = [rule for rule in section["rules"] if rule["id"] == rule_id]
    return rule["key_exprs"]


def test_a_service_may_put_exactly_the_topics_it_declares_and_its_diagnostics_under_its_vehicle_with_their_markers():
    grant = service_grant(service_entry("control"), "car7")
    assert grant.subject == "control"
    assert grant.puts == ("coopdrive/car7/control/command", "coopdrive/car7/diagnostics/control",
                          "coopdrive/car7/@step/control/command", "coopdrive/car7/@step/diagnostics/control")
    assert grant.subscriptions == ("coopdrive/car7/ego/state", "coopdrive/car7/planner/behaviour",
                                   "coopdrive/car7/scene", "coopdrive/car7/@step/ego/state",
                                   "coopdrive/car7/@step/planner/behaviour", "coopdrive/car7/@step/scene")
    assert grant.tokens == ("coopdrive/car7/_alive/control",)
    assert grant.queryables == ("coopdrive/car7/_info/control",)


@pytest.mark.parametrize("grant", bus_grants("ego", ("laptop",)), ids=lambda grant: grant.subject)
def test_every_grant_stays_under_its_own_vehicle(grant):
    keys = grant.puts + grant.subscriptions + grant.tokens + grant.queryables + grant.queries
    assert keys and all(key.startswith("coopdrive/ego/") for key in keys)


def test_the_gateway_may_put_only_its_command_topics_and_reads_the_whole_vehicle():
    entry = service_entry("gateway")
    grant = service_grant(entry, "ego")
    commands = [f"coopdrive/ego/{topic.name}" for topic in published_by(entry)]
    assert commands and all("/gateway/" in key for key in commands)
    topics = (*commands, "coopdrive/ego/diagnostics/gateway")
    assert grant.puts == (*topics, *(key.replace("coopdrive/ego/", "coopdrive/ego/@step/") for key in topics))
    assert grant.subscriptions[0] == "coopdrive/ego/**"
    assert all(key.startswith("coopdrive/ego/@step/") for key in grant.subscriptions[1:])


def test_actuation_may_put_the_cars_can_frames_in_the_simulators_place_and_nobody_else_may():
    grants = {grant.subject: grant for grant in bus_grants("ego")}
    assert "coopdrive/ego/can/vehicle" in grants["actuation"].puts
    assert [name for name, grant in grants.items() if "coopdrive/ego/can/vehicle" in grant.puts] == ["actuation"]


def test_the_simulator_gets_no_certificate_since_there_is_no_world_on_a_car():
    assert "sim" not in [grant.subject for grant in bus_grants("ego")]


def test_an_observer_only_subscribes_asks_the_services_info_and_shows_its_presence():
    grant = observer_grant("laptop", "ego")
    assert (grant.puts, grant.queryables) == ((), ())
    assert grant.tokens == ("coopdrive/ego/_alive/laptop",)
    assert grant.subscriptions == ("coopdrive/ego/**",)
    assert grant.queries == ("coopdrive/ego/_info/*",)


@pytest.mark.parametrize("name", ["control", "gateway", "router", "ca"])
def test_an_observer_may_not_take_the_name_of_a_service_or_of_the_bus_itself(name):
    with pytest.raises(ValueError, match=f"observer name '{name}' is taken"):
        observer_grant(name, "ego")


@pytest.mark.parametrize("vehicle", ["e/go", "*", "", "eg$o"])
def test_a_vehicle_id_that_is_not_one_key_chunk_is_refused(vehicle):
    with pytest.raises(ValueError, match="vehicle id"):
        bus_grants(vehicle)


def test_adding_a_topic_to_a_services_declaration_adds_it_to_its_rules(monkeypatch):
    entry = service_entry("planner")
    declarations = declarations_of(entry)
    added = Topic("planner/debug", diagnostics_pb2.Diagnostics, "planner", stepped=False)
    monkeypatch.setattr(declarations, "PUBLISHES", (*declarations.PUBLISHES, added))
    monkeypatch.setattr(declarations, "SUBSCRIBES", (*declarations.SUBSCRIBES, "v2x/status"))
    section = access_control(bus_grants("ego"), "ego")
    assert "coopdrive/ego/planner/debug" in rule_keys(section, "planner publishes")
    assert "coopdrive/ego/v2x/status" in rule_keys(section, "planner subscribes")
    assert "coopdrive/ego/v2x/status" in rule_keys(section, "planner receives")
    assert "coopdrive/ego/planner/debug" not in rule_keys(section, "control publishes")


def test_the_router_denies_by_default_and_gives_each_certificate_only_its_own_rules():
    section = access_control(bus_grants("ego", ("laptop",)), "ego")
    assert section["enabled"] is True and section["default_permission"] == "deny"
    ids = [rule["id"] for rule in section["rules"]]
    assert len(ids) == len(set(ids))
    assert all(rule["permission"] == "allow" and rule["key_exprs"] for rule in section["rules"])
    subjects = {subject["id"]: subject["cert_common_names"] for subject in section["subjects"]}
    assert subjects["control"] == ["control"] and subjects["laptop"] == ["laptop"]
    policies = {policy["id"]: policy for policy in section["policies"]}
    assert set(policies) == set(subjects)
    assert "control publishes" in policies["control"]["rules"]
    assert not any(rule.startswith("control ") for rule in policies["planner"]["rules"])
    assert not any("publishes" in rule for rule in policies["laptop"]["rules"])


def test_each_puts_rule_is_an_ingress_put_and_each_reception_an_egress_put():
    section = access_control(bus_grants("ego"), "ego")
    by_id = {rule["id"]: rule for rule in section["rules"]}
    assert (by_id["scene publishes"]["flows"], by_id["scene publishes"]["messages"]) == (["ingress"], ["put"])
    assert (by_id["scene receives"]["flows"], by_id["scene receives"]["messages"]) == (["egress"], ["put"])
    assert by_id["scene subscribes"]["messages"] == ["declare_subscriber"]


def test_a_declaration_standing_in_for_a_topic_the_simulator_does_not_publish_is_refused(monkeypatch):
    declarations = importlib.import_module(service_entry("actuation").declarations)
    monkeypatch.setattr(declarations, "PUBLISHES_ON_VEHICLE", ("control/command",), raising=False)
    with pytest.raises(ValueError, match="topics the sim service does not publish: control/command"):
        service_grant(service_entry("actuation"), "ego")
