"""A finished clock master keeps its bus open until the launcher that started it stops it: its last messages
(the result) may still wait in its send queue behind a loaded launcher's backlog."""

import threading
import time
from types import SimpleNamespace

from coopdrive.runtime.launcher_watch import LAUNCHER_PID_VARIABLE
from coopdrive.runtime.runner import ServiceRunner


def test_a_finished_master_started_by_a_launcher_waits_for_its_sigterm(monkeypatch):
    monkeypatch.setenv(LAUNCHER_PID_VARIABLE, "12345")
    runner = SimpleNamespace(_stop_reason="scenario finished")
    threading.Timer(0.3, lambda: setattr(runner, "_stop_reason", "SIGTERM")).start()
    started = time.monotonic()
    ServiceRunner._linger_for_the_launcher(runner)
    assert runner._stop_reason == "SIGTERM" and time.monotonic() - started >= 0.3


def test_a_master_run_by_hand_ends_at_once(monkeypatch):
    monkeypatch.delenv(LAUNCHER_PID_VARIABLE, raising=False)
    runner = SimpleNamespace(_stop_reason="scenario finished")
    started = time.monotonic()
    ServiceRunner._linger_for_the_launcher(runner)
    assert time.monotonic() - started < 0.1
