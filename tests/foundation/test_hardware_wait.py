"""A deployed service whose device is missing waits for it with one diagnostic line, instead of exiting into its
container's restart loop, and still stops cleanly."""

import signal
import time

import pytest

from coopdrive.runtime.hardware_wait import run_waiting_for_hardware
from coopdrive.runtime.service import HardwareUnavailable


def test_a_missing_gnss_port_is_reported_once_while_the_service_keeps_trying_and_sigterm_ends_it(spawn, endpoint,
                                                                                                tmp_path):
    port = tmp_path / "gnss0"
    process = spawn("service", "geolocation", "--connect", endpoint, "--set", f"gnss_port={port}",
                    "--set", "gnss_open_timeout_s=0.2", "--hardware-retry", "0.2")
    first = process.stderr.readline()  # after the first attempt, however slow the start on a loaded machine
    assert str(port) in first and "trying again every 0.2 s" in first, first
    time.sleep(2.0)  # several more attempts
    assert process.poll() is None, process.stderr.read()
    process.send_signal(signal.SIGTERM)
    assert process.wait(timeout=10) == 0
    assert process.stderr.read() == ""  # said once


def test_without_hardware_retry_a_missing_port_still_exits_with_one_line(spawn, endpoint, tmp_path):
    process = spawn("service", "geolocation", "--connect", endpoint, "--set", f"gnss_port={tmp_path / 'gnss0'}",
                    "--set", "gnss_open_timeout_s=0.2")
    assert process.wait(timeout=60) == 1
    assert len(process.stderr.read().splitlines()) == 1


def test_the_device_appearing_later_lets_the_next_attempt_run():
    attempts = []

    class Runner:
        stopping = False

        def run(self):
            attempts.append(1)
            if len(attempts) < 3:
                raise HardwareUnavailable("can0 is down")
            return "done"

    run_waiting_for_hardware(Runner, 0.01, "ego/actuation")
    assert len(attempts) == 3


def test_without_a_retry_interval_the_failure_goes_up():
    class Runner:
        stopping = False

        def run(self):
            raise HardwareUnavailable("can0 is down")

    with pytest.raises(HardwareUnavailable):
        run_waiting_for_hardware(Runner, None, "ego/actuation")
