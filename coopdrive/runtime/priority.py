"""Lowering a service process's CPU priority, for services that serve people rather than the control loop."""

from __future__ import annotations

import os
from pathlib import Path

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
