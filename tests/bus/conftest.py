"""Fixtures of the secured bus: the credentials `coopdrive pki bus` makes for the test's router port, and a real
`coopdrive router` process on them."""

import os
import subprocess
from pathlib import Path

import pytest

from coopdrive.launch.ports import free_tcp_port
from tests.bus.secure_bus import ROUTER_LOG_FILTER, OBSERVER, VEHICLE, coopdrive, wait_for_log


@pytest.fixture
def router_endpoint() -> str:
    return f"tls/127.0.0.1:{free_tcp_port()}"


@pytest.fixture
def credentials(tmp_path, router_endpoint) -> Path:
    directory = tmp_path / "bus"
    made = coopdrive("pki", "bus", str(directory), "--vehicle", VEHICLE, "--observer", OBSERVER,
                     "--router", router_endpoint)
    assert made.returncode == 0, made.stderr
    return directory


@pytest.fixture
def router_log(spawn, credentials, router_endpoint, tmp_path) -> Path:
    """Starts the router the credentials describe, listening on the test's port; the path of its output (Zenoh's log
    goes to stdout, with the router's own lines)."""
    log = tmp_path / "router.log"
    with open(log, "w") as output:
        spawn("router", "--config", str(credentials / "router" / "zenohd.json5"), "--listen", router_endpoint,
              stdout=output, stderr=subprocess.STDOUT, env={**os.environ, "RUST_LOG": ROUTER_LOG_FILTER})
    wait_for_log(log, "listening")
    return log
