"""Lowering CPU priority: a service process's threads, for services that serve people rather than the control loop,
and a whole session's, for a sweep that runs in the background."""

from __future__ import annotations

import os
from pathlib import Path

from coopdrive.runtime.config import ConfigError

MAX_NICE = 19


def lower_cpu_priority(by: int) -> None:
    """Adds `by` to the nice value of every thread of this process.

    Linux keeps a nice value per thread and os.nice() changes only the caller's, while libraries may have
    started threads at import (the BLAS pool, for one), so each thread is lowered; threads started later
    inherit from the thread that starts them.
    """
    tasks = Path("/proc/self/task")
    thread_ids = [int(task.name) for task in tasks.iterdir()] if tasks.is_dir() else [0]
    for thread_id in thread_ids:
        try:
            current = os.getpriority(os.PRIO_PROCESS, thread_id)
            os.setpriority(os.PRIO_PROCESS, thread_id, min(current + by, MAX_NICE))
        except (ProcessLookupError, PermissionError):
            pass  # a thread that ended meanwhile; raising a priority back is not what this does


# A sweep run beside other work sets this to MAX_NICE (tools/ci_sweep.sh with BESIDE=1).
SESSION_NICE_VARIABLE = "COOPDRIVE_SESSION_NICE"
AUTOGROUP = Path("/proc/self/autogroup")
MIN_NICE = -20


def nice_session_as_asked() -> None:
    """Gives this process's session the nice value COOPDRIVE_SESSION_NICE asks for, if it asks.

    Linux shares the cores between sessions first (the scheduler's autogroups) and by each thread's nice value only
    within one, and a run starts every service in a session of its own: a whole run started under `nice` still takes
    an even share of the cores from whatever runs beside it. Every coopdrive command sets its session's nice value
    here, so a background sweep stays in the background. A kernel without autogroups (no file to write), or one
    that refuses, leaves the sessions as they are: there the threads' own nice values decide.
    Raises ConfigError for a value that is not a nice value.
    """
    text = os.environ.get(SESSION_NICE_VARIABLE)
    if not text:
        return
    try:
        nice = int(text)
    except ValueError:
        nice = None
    if nice is None or not MIN_NICE <= nice <= MAX_NICE:
        raise ConfigError(f"{SESSION_NICE_VARIABLE}={text!r}: a nice value is a whole number from {MIN_NICE} to "
                          f"{MAX_NICE}")
    try:
        AUTOGROUP.write_text(str(nice))
    except OSError:
        pass
