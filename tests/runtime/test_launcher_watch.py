"""A service that a run launched ends when its launcher is killed outright, as a lost sweep worker's would."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from coopdrive.launch.processes import ServiceProcesses

# The launcher starts a service the way ServiceProcesses does (its own session, its environment) and waits.
LAUNCHER = """
import subprocess, sys
from coopdrive.launch.processes import ServiceProcesses
child = subprocess.Popen([sys.executable, "-c", sys.argv[1]], start_new_session=True,
                         env=ServiceProcesses.environment())
print(child.pid, flush=True)
child.wait()
"""
SERVICE = "from coopdrive.runtime.launcher_watch import exit_with_launcher; exit_with_launcher(); " \
          "import time; time.sleep(60)"


def running(pid: int) -> bool:
    """Alive and not a zombie: an orphan's new parent may be slow to reap it."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except (FileNotFoundError, ProcessLookupError):
        return False


def test_a_launched_service_stops_within_a_second_or_two_of_its_launchers_death():
    launcher = subprocess.Popen([sys.executable, "-c", LAUNCHER, SERVICE], stdout=subprocess.PIPE, text=True)
    service_pid = int(launcher.stdout.readline())
    try:
        time.sleep(1.0)
        assert running(service_pid)  # it watches; it does not end on its own
        launcher.send_signal(signal.SIGKILL)
        launcher.wait()
        deadline = time.monotonic() + 10.0
        while running(service_pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not running(service_pid)
    finally:
        if running(service_pid):
            os.kill(service_pid, signal.SIGKILL)


def test_a_process_not_launched_by_a_run_has_no_launcher_to_watch(monkeypatch):
    from coopdrive.runtime import launcher_watch

    monkeypatch.delenv(launcher_watch.LAUNCHER_PID_VARIABLE, raising=False)
    started = []
    monkeypatch.setattr(launcher_watch.threading, "Thread", lambda *a, **k: started.append(k))
    launcher_watch.exit_with_launcher()
    assert started == []
