"""When a session over mutual TLS does not open, its own files say why in one line."""

import datetime

import pytest
import zenoh

from coopdrive.bus.bus_authority import BusAuthority, write_pair
from coopdrive.bus.bus_credentials import BusCredentialsRequest, write_bus_credentials
from coopdrive.bus.credential_check import credentials_problem

NOW = datetime.datetime(2026, 6, 1, 12, 0, tzinfo=datetime.timezone.utc)


@pytest.fixture
def credentials(tmp_path):
    write_bus_credentials(BusCredentialsRequest(tmp_path / "bus", "ego", days=10), now=NOW)
    return tmp_path / "bus"


def control_config(credentials) -> zenoh.Config:
    return zenoh.Config.from_file(str(credentials / "control" / "zenoh.json5"))


def test_valid_credentials_have_no_problem(credentials):
    assert credentials_problem(control_config(credentials), NOW + datetime.timedelta(days=1)) is None


def test_a_certificate_past_its_days_is_named_with_the_day_it_expired(credentials):
    problem = credentials_problem(control_config(credentials), NOW + datetime.timedelta(days=11))
    assert problem.startswith(f"certificate {credentials / 'control' / 'cert.pem'} expired on 2026-06-11 12:00 UTC")
    assert "coopdrive pki bus DIR --vehicle ID" in problem


def test_a_certificate_not_yet_valid_asks_about_the_clock(credentials):
    problem = credentials_problem(control_config(credentials), NOW - datetime.timedelta(days=1))
    assert "is not valid before 2026-06-01 11:55 UTC" in problem and "clock" in problem


def test_a_config_without_a_certificate_says_there_is_none(credentials):
    config = control_config(credentials)
    config.insert_json5("transport/link/tls/connect_certificate", "null")
    assert credentials_problem(config, NOW).startswith("no client certificate")


def test_a_certificate_another_ca_signed_is_named(credentials, tmp_path):
    other = BusAuthority.create("another CA", days=10, now=NOW)
    write_pair(*other.issue("control", days=10, now=NOW), credentials / "control" / "cert.pem",
               credentials / "control" / "key.pem")
    problem = credentials_problem(control_config(credentials), NOW + datetime.timedelta(days=1))
    assert "is not signed by the bus CA" in problem


def test_a_session_without_tls_endpoints_is_not_judged():
    config = zenoh.Config()
    config.insert_json5("connect/endpoints", '["tcp/127.0.0.1:7447"]')
    assert credentials_problem(config, NOW) is None
