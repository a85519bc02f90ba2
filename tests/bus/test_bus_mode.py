"""The bus mode a session's diagnostics and the gateway's /health tell, read off the session's config."""

from coopdrive.bus import BusConfig
from coopdrive.bus.bus_mode import bus_mode
from tests.bus.secure_bus import OBSERVER, client_config


def test_a_session_with_a_generated_client_config_is_mtls(credentials):
    assert bus_mode(BusConfig(zenoh_config_file=client_config(credentials, OBSERVER)).to_zenoh()) == "mtls"


def test_a_session_on_loopback_tcp_only_is_plain_loopback():
    assert bus_mode(BusConfig(connect=["tcp/127.0.0.1:7447"]).to_zenoh()) == "plain-loopback"


def test_a_session_reaching_another_computer_over_tcp_is_plain():
    assert bus_mode(BusConfig(connect=["tcp/192.168.1.20:7447"]).to_zenoh()) == "plain"


def test_a_session_listening_on_every_interface_is_plain():
    assert bus_mode(BusConfig(listen=["tcp/0.0.0.0:0"]).to_zenoh()) == "plain"
