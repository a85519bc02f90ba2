"""TokenBook and the token settings of GatewayConfig."""

from pathlib import Path

import pytest
import yaml
from pydantic import ValidationError

from coopdrive.services.gateway.auth import Command, Principal, TokenBook
from coopdrive.services.gateway.config import GatewayConfig, Role


def book(readonly_open: bool = True) -> TokenBook:
    return TokenBook({"alice": ("alice-token", Role.OPERATOR), "wall": ("wall-token", Role.OBSERVER)},
                     readonly_open, read_token="read-token")


def test_a_token_is_known_by_its_name_and_role():
    assert book().identify("alice-token") == Principal("alice", Role.OPERATOR)
    assert book().identify("wall-token") == Principal("wall", Role.OBSERVER)
    assert book().identify("read-token") == Principal("read_token", Role.OBSERVER)
    assert book().identify("alice-token ") is None
    assert book().identify(None) is None


def test_operators_may_give_every_command_and_observers_none():
    alice, wall = book().identify("alice-token"), book().identify("wall-token")
    assert all(alice.may(command) for command in Command)
    assert not any(wall.may(command) for command in Command)


def test_closed_reading_needs_a_known_token():
    assert book(readonly_open=True).may_read(None)
    assert not book(readonly_open=False).may_read(None)
    assert book(readonly_open=False).may_read("wall-token")


def test_the_config_reads_named_tokens_with_roles():
    config = GatewayConfig(readonly_open=False, tokens={"alice": {"token": "alice-token", "role": "operator"}})
    assert TokenBook.from_config(config).identify("alice-token") == Principal("alice", Role.OPERATOR)


def test_short_tokens_unknown_roles_and_shared_tokens_are_config_errors():
    with pytest.raises(ValidationError):
        GatewayConfig(tokens={"alice": {"token": "short", "role": "operator"}})
    with pytest.raises(ValidationError):
        GatewayConfig(tokens={"alice": {"token": "alice-token", "role": "admin"}})
    with pytest.raises(ValidationError, match="share one token"):
        GatewayConfig(tokens={"a": {"token": "same-token", "role": "operator"},
                              "b": {"token": "same-token", "role": "observer"}})


def test_mutual_tls_is_configured_with_a_client_ca(tmp_path):
    config = GatewayConfig(tls={"certfile": tmp_path / "c.pem", "keyfile": tmp_path / "k.pem",
                                "client_ca": tmp_path / "ca.pem"})
    assert config.tls.client_ca == tmp_path / "ca.pem"


def test_the_example_gateway_config_is_valid():
    example = Path(__file__).resolve().parents[2] / "services" / "gateway" / "examples" / "gateway-secure.yaml"
    config = GatewayConfig.model_validate(yaml.safe_load(example.read_text()))
    assert config.tls.client_ca is not None and not config.readonly_open
    assert {entry.role for entry in config.tokens.values()} == {Role.OPERATOR, Role.OBSERVER}


def test_the_example_zenoh_config_is_what_the_pki_bus_command_writes_for_the_vehicle_profile(tmp_path):
    import subprocess
    import sys

    import zenoh

    example = Path(__file__).resolve().parents[2] / "services" / "gateway" / "examples" / "zenoh-secure.json5"
    made = subprocess.run([sys.executable, "-m", "coopdrive.cli", "pki", "bus", str(tmp_path / "credentials"),
                           "--vehicle", "ego", "--observer", "foxglove", "--observer", "recorder",
                           "--mounted-at", "/credentials"], capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    written = (tmp_path / "credentials" / "router" / "zenohd.json5").read_text()
    assert example.read_text().split("\n", 3)[3] == written
    config = zenoh.Config.from_file(str(example))
    assert config.get_json("access_control/default_permission") == '"deny"'
    assert config.get_json("transport/link/tls/enable_mtls") == "true"
