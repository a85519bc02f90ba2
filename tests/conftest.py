"""Shared fixtures: free loopback ports and processes that are always cleaned up; the files that start whole runs
are handed to the test workers first."""

import os
import signal
import subprocess
import sys

import pytest

from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from tests.system_packages import fail_if_ci_skipped_for_a_package

WHOLE_RUN = "whole_run"


def pytest_configure(config):
    config.addinivalue_line("markers", f"{WHOLE_RUN}: the file starts whole scenario runs (tens of seconds each)")


def pytest_collection_modifyitems(items):
    """Files marked `whole_run` go first, each file's tests kept together and in order. `make test` hands files to
    its workers in this order (`--no-loadscope-reorder`): xdist's own order, most tests first, put these files of a
    few tests behind one long run last, and the suite ended on both workers running them one after the other."""
    items.sort(key=lambda item: item.get_closest_marker(WHOLE_RUN) is None)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Under CI a test skipped for a missing system package fails (tests/system_packages.py)."""
    outcome = yield
    fail_if_ci_skipped_for_a_package(outcome.get_result(), os.environ)


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
