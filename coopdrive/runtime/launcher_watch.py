"""A service process that a run launched ends when that launcher dies.

The launcher starts each service in a session of its own (so a Ctrl-C reaches the launcher alone, which stops
them in order). When the launcher itself is killed outright (a sweep's worker killed by a test, the OOM killer
or a lost host), nothing else would stop them: a stack waiting for its simulator's clock would wait forever and
its processes would keep their CPU and ports. The launcher names itself in LAUNCHER_PID_VARIABLE; a service told
so watches it and stops the ordinary way (SIGTERM) once it has ended: as its parent, or (a service forked by the
launcher's preloaded server, whose parent is that server) through a process descriptor of the launcher.
"""

from __future__ import annotations

import os
import select
import signal
import threading
import time

from coopdrive.exit_status import EXIT_ORPHANED

LAUNCHER_PID_VARIABLE = "COOPDRIVE_LAUNCHER_PID"
POLL_S = 0.5
# After the SIGTERM a service normally stops within a step; past this it is ended without cleanup.
STOP_GRACE_S = 5.0


def launcher_environment() -> dict[str, str]:
    """What a launcher adds to a service's environment so the service ends with it."""
    return {LAUNCHER_PID_VARIABLE: str(os.getpid())}


def launched_by_a_run() -> bool:
    """Whether a run's launcher started this process (and will stop it)."""
    return (os.environ.get(LAUNCHER_PID_VARIABLE) or "").isdigit()


def exit_with_launcher() -> None:
    """Starts the watch when this process was launched by a run; does nothing otherwise."""
    text = os.environ.get(LAUNCHER_PID_VARIABLE)
    if not text or not text.isdigit():
        return
    threading.Thread(target=_watch, args=(int(text),), name="launcher-watch", daemon=True).start()


def _watch(launcher_pid: int) -> None:
    if os.getppid() == launcher_pid:
        # The parent changes only when it dies: the orphan is re-parented to init or a subreaper.
        while os.getppid() == launcher_pid:
            time.sleep(POLL_S)
    else:
        _wait_for_exit(launcher_pid)
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(STOP_GRACE_S)
    os._exit(EXIT_ORPHANED)


def _wait_for_exit(launcher_pid: int) -> None:
    """A launcher that is not our parent (it had the preloaded server fork us): its process descriptor, which
    names that process and no later one with its number, becomes readable when it ends."""
    try:
        descriptor = os.pidfd_open(launcher_pid)
    except ProcessLookupError:
        return  # it has already ended
    with select.epoll() as ended:
        ended.register(descriptor, select.EPOLLIN)
        while not ended.poll():
            pass
    os.close(descriptor)
