"""A process with Zenoh's native threads hears SIGINT and SIGTERM whichever of its threads the kernel hands them to:
the signal is sent here to a thread that is not the main one (tgkill), as the kernel may do on its own."""

import ctypes
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from coopdrive.runtime.signal_wait import SIGNAL_POLL_S, wait_hearing_signals
from tests.recording.live_bus import wait_recording

# The stop grace docs/how-to/record-replay.md states for a stopped process.
STOP_WITHIN_S = 3.0
START_TIMEOUT_S = 60.0


def other_thread_of(pid: int) -> int:
    """A thread of the process that is not its main thread, once it has some (Zenoh starts its own)."""
    deadline = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < deadline:
        others = [int(tid) for tid in os.listdir(f"/proc/{pid}/task") if int(tid) != pid]
        if others:
            return max(others)
        time.sleep(0.1)
    raise AssertionError(f"process {pid} started no thread")


def signal_thread(pid: int, tid: int, signum: int) -> None:
    assert ctypes.CDLL(None, use_errno=True).tgkill(pid, tid, signum) == 0, os.strerror(ctypes.get_errno())


def ends_within(process: subprocess.Popen, seconds: float) -> bool:
    try:
        process.wait(timeout=seconds)
        return True
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
        return False


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_recorder_stops_on_a_signal_handed_to_one_of_zenoh_s_threads(tmp_path, signum):
    endpoint = loopback_endpoint(free_tcp_port())
    hub = Bus(BusConfig(listen=[endpoint]))
    path = tmp_path / "drive.mcap"
    recorder = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "record", str(path), "--connect", endpoint],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        wait_recording(hub)
        signal_thread(recorder.pid, other_thread_of(recorder.pid), signum)
        assert ends_within(recorder, STOP_WITHIN_S), "the recorder did not hear the signal"
    finally:
        if recorder.poll() is None:
            recorder.kill()
        hub.close()
    assert recorder.returncode == 0, recorder.stderr.read()
    assert b"recorded" in recorder.stdout.read()


def test_a_router_stops_on_a_signal_handed_to_one_of_zenoh_s_threads():
    """Exit code 0: its own handler ended it (the default action, before the handler is set, would give -15)."""
    endpoint = loopback_endpoint(free_tcp_port())
    router = subprocess.Popen([sys.executable, "-m", "coopdrive.cli", "router", "--listen", endpoint],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert "listening" in router.stdout.readline()
        time.sleep(0.5)  # from its line to its wait for the signal
        signal_thread(router.pid, other_thread_of(router.pid), signal.SIGTERM)
        assert ends_within(router, STOP_WITHIN_S), "the router did not hear the signal"
    finally:
        if router.poll() is None:
            router.kill()
    assert router.returncode == 0, router.stderr.read()


def test_a_wait_hearing_signals_returns_when_the_event_is_set_or_the_time_is_up():
    event = threading.Event()
    started = time.monotonic()
    assert not wait_hearing_signals(event, 3 * SIGNAL_POLL_S)
    assert time.monotonic() - started >= 3 * SIGNAL_POLL_S
    threading.Timer(SIGNAL_POLL_S, event.set).start()
    assert wait_hearing_signals(event)
