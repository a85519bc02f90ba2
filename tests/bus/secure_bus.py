"""What the tests of the vehicle's secured bus share: its vehicle and observer, the command line, sessions opened with
a certificate holder's generated config, and waiting for the router's log (fixtures: tests/bus/conftest.py)."""

import subprocess
import sys
import time
from pathlib import Path

import zenoh

from coopdrive.bus import topic_named
from coopdrive.bus.bus_credentials import CLIENT_CONFIG

DEADLINE_S = 30.0
VEHICLE = "ego"
OBSERVER = "laptop"
# The router logs its warnings (a refused certificate, a link closed at its expiry) and its access control each
# decision at trace level: the tests read when it judged a put.
ROUTER_LOG_FILTER = "warn,zenoh::net::routing::interceptor::access_control=trace"


def coopdrive(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=120)


def client_config(credentials: Path, name: str) -> str:
    return str(credentials / name / CLIENT_CONFIG)


def open_as(credentials: Path, name: str) -> zenoh.Session:
    """A raw session with `name`'s certificate: what a forger holding it could do, not what coopdrive's Bus does."""
    return zenoh.open(zenoh.Config.from_file(client_config(credentials, name)))


def message(topic: str, sender: str):
    """An empty message of `topic`'s type, its header naming `sender`."""
    typed = topic_named(topic).message_type()
    typed.header.sender = sender
    return typed


def wait_until(condition, what: str) -> None:
    end = time.monotonic() + DEADLINE_S
    while not condition():
        assert time.monotonic() < end, f"never: {what}"
        time.sleep(0.05)


def wait_for_log(log: Path, text: str) -> None:
    wait_until(lambda: text in log.read_text(errors="replace"), f"the router logged {text!r}")
