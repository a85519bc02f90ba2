"""A finished clock master keeps its bus open until the launcher that started it stops it: its last messages
(the result) may still wait in its send queue behind a loaded launcher's backlog."""

import threading
import time
from types import SimpleNamespace

from coopdrive.runtime.launcher_watch import LAUNCHER_PID_VARIABLE
from coopdrive.runtime.runner import ServiceRunner

SIGTERM_AFTER_S = 0.3
AT_ONCE_S = 0.1


def finished_master():
    """What _linger_for_the_launcher and on_signal read of a runner whose scenario has finished."""
    return SimpleNamespace(_signalled=threading.Event(), _stop_reason="scenario finished",
                           request_stop=lambda reason: None)


def test_a_finished_master_started_by_a_launcher_waits_for_its_sigterm(monkeypatch):
    monkeypatch.setenv(LAUNCHER_PID_VARIABLE, "12345")
    runner = finished_master()
    # Read before the timer starts: the signal comes SIGTERM_AFTER_S after the timer's start, not after this.
    started = time.monotonic()
    threading.Timer(SIGTERM_AFTER_S, lambda: ServiceRunner.on_signal(runner, "SIGTERM")).start()
    ServiceRunner._linger_for_the_launcher(runner)
    assert runner._signalled.is_set() and time.monotonic() - started >= SIGTERM_AFTER_S


def test_a_sigterm_that_came_before_the_master_finished_ends_its_wait_at_once(monkeypatch):
    monkeypatch.setenv(LAUNCHER_PID_VARIABLE, "12345")
    runner = finished_master()
    ServiceRunner.on_signal(runner, "SIGTERM")
    started = time.monotonic()
    ServiceRunner._linger_for_the_launcher(runner)
    assert time.monotonic() - started < AT_ONCE_S


def test_a_master_run_by_hand_ends_at_once(monkeypatch):
    monkeypatch.delenv(LAUNCHER_PID_VARIABLE, raising=False)
    runner = finished_master()
    started = time.monotonic()
    ServiceRunner._linger_for_the_launcher(runner)
    assert time.monotonic() - started < AT_ONCE_S
