"""A service that a run launched ends when its launcher is killed outright, as a lost sweep worker's would."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path


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


def killing_the_launcher_stops_the_service(launcher: subprocess.Popen, watched_s: float) -> bool:
    """Kills the launcher once its service has been watching for `watched_s`; whether the service then stops
    within the launcher watch's poll and stop grace."""
    service_pid = int(launcher.stdout.readline())
    try:
        time.sleep(watched_s)
        assert running(service_pid)  # it watches; it does not end on its own
        launcher.send_signal(signal.SIGKILL)
        launcher.wait()
        deadline = time.monotonic() + 10.0
        while running(service_pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        return not running(service_pid)
    finally:
        if running(service_pid):
            os.kill(service_pid, signal.SIGKILL)


def test_a_launched_service_stops_within_a_second_or_two_of_its_launchers_death():
    launcher = subprocess.Popen([sys.executable, "-c", LAUNCHER, SERVICE], stdout=subprocess.PIPE, text=True)
    assert killing_the_launcher_stops_the_service(launcher, watched_s=1.0)


# A launcher that forks a stack's group the way a run does (ServiceProcesses: from the preloaded server); the group
# waits for a clock that never comes, on an endpoint where nobody listens.
FORKING_LAUNCHER = """
import json, sys, time
from pathlib import Path
from coopdrive.launch.processes import ServiceProcesses
spec = Path(sys.argv[1])
spec.write_text(json.dumps([{"service": "planner", "vehicle": "v", "config": {}}]))
processes = ServiceProcesses("tcp/127.0.0.1:1")
processes._spawn("v/group", [], ["group", str(spec)])
print(processes.processes["v/group"].pid, flush=True)
time.sleep(120)
"""


def test_a_forked_service_stops_within_seconds_of_its_launchers_death(tmp_path):
    """Its parent is the preloaded server, which outlives the launcher while any service it forked lives."""
    launcher = subprocess.Popen([sys.executable, "-c", FORKING_LAUNCHER, str(tmp_path / "group.json")],
                                stdout=subprocess.PIPE, text=True)
    assert killing_the_launcher_stops_the_service(launcher, watched_s=2.0)


def test_a_process_not_launched_by_a_run_has_no_launcher_to_watch(monkeypatch):
    from coopdrive.runtime import launcher_watch

    monkeypatch.delenv(launcher_watch.LAUNCHER_PID_VARIABLE, raising=False)
    started = []
    monkeypatch.setattr(launcher_watch.threading, "Thread", lambda *a, **k: started.append(k))
    launcher_watch.exit_with_launcher()
    assert started == []
