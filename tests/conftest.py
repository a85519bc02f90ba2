"""Shared fixtures: free loopback ports and processes that are always cleaned up."""

import os
import signal
import subprocess
import sys

import pytest

from coopdrive.launch.ports import free_tcp_port, loopback_endpoint


@pytest.fixture
def endpoint() -> str:
    return loopback_endpoint(free_tcp_port())


@pytest.fixture
def hub(endpoint):
    """A Bus listening on `endpoint`, where the processes a test spawns connect; closed at the end."""
    from coopdrive.bus import Bus, BusConfig

    bus = Bus(BusConfig(listen=[endpoint]))
    yield bus
    bus.close()


@pytest.fixture
def spawn():
    """Starts `python -m coopdrive.cli ...` processes and kills any still running at the end."""
    started: list[subprocess.Popen] = []

    def start(*args: str, **kwargs) -> subprocess.Popen:
        process = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", *args], start_new_session=True,
                                   stdout=kwargs.pop("stdout", subprocess.PIPE),
                                   stderr=kwargs.pop("stderr", subprocess.PIPE), text=True, **kwargs)
        started.append(process)
        return process

    yield start
    for process in started:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@pytest.fixture
def shared_data():
    """The folder of real recordings (NMEA, CAN, V2X captures): see tests/shared_data.py."""
    from tests.shared_data import shared_data_dir

    return shared_data_dir()
