"""Fixtures of the CAN tests."""

import pytest

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint


@pytest.fixture
def hub():
    """A Zenoh session listening on a free loopback port (the run's hub): (bus, endpoint)."""
    endpoint = loopback_endpoint(free_tcp_port())
    bus = Bus(BusConfig(listen=[endpoint]))
    yield bus, endpoint
    bus.close()
