"""WorkerProfile: a service worker's own cProfile, for finding where a run's time goes (docs/performance.md).

Set COOPDRIVE_PROFILE_DIR and every service worker, in every process of a run, writes
<dir>/<vehicle>-<service>.prof when it stops (read it with `python -m pstats` or snakeviz); a group in simulated
time, whose services share one worker (shared_worker.py), writes <dir>/<vehicle>-group.prof. Only the worker's
thread is profiled (handlers, triggers, lockstep), not Zenoh's threads, and start-up is left out.

cProfile times calls on the wall clock, so a worker that waits for its queue, or for the interpreter's lock held
by another thread, shows that wait as time in the call it waited in. COOPDRIVE_PROFILE_CLOCK=cpu times them on the
thread's own CPU clock instead: the profile then says where the CPU went, and waits vanish from it. Reading that
clock is a system call per event, so a CPU profile runs slower than a wall-clock one (about four times on a
stack's worker) and its totals are inflated alike; compare shares, not milliseconds.
"""

from __future__ import annotations

import cProfile
import logging
import os
import time
from pathlib import Path

log = logging.getLogger(__name__)

PROFILE_DIR_VARIABLE = "COOPDRIVE_PROFILE_DIR"
PROFILE_CLOCK_VARIABLE = "COOPDRIVE_PROFILE_CLOCK"
# COOPDRIVE_PROFILE_CLOCK values -> the timer cProfile reads (None: cProfile's own, the wall clock).
PROFILE_CLOCKS = {"wall": None, "cpu": time.thread_time}


class WorkerProfile:
    def __init__(self, out_file: Path | None, clock: str = "wall"):
        """clock: "wall" or "cpu" (PROFILE_CLOCKS); any other is named in a warning and the wall clock used, as a
        profile is worth having and a typo in it no reason to stop a service."""
        if clock not in PROFILE_CLOCKS:
            log.warning("%s=%r is none of %s: profiling on the wall clock", PROFILE_CLOCK_VARIABLE, clock,
                        ", ".join(PROFILE_CLOCKS))
            clock = "wall"
        self._out_file = out_file
        self._profiler = None
        if out_file is not None:
            timer = PROFILE_CLOCKS[clock]
            self._profiler = cProfile.Profile(timer) if timer is not None else cProfile.Profile()

    @classmethod
    def from_environment(cls, name: str) -> WorkerProfile:
        folder = os.environ.get(PROFILE_DIR_VARIABLE)
        clock = os.environ.get(PROFILE_CLOCK_VARIABLE) or "wall"
        return cls(Path(folder) / f"{name}.prof" if folder else None, clock)

    def __enter__(self) -> WorkerProfile:
        if self._profiler is not None:
            self._profiler.enable()
        return self

    def __exit__(self, *exc: object) -> None:
        if self._profiler is None:
            return
        self._profiler.disable()
        self._out_file.parent.mkdir(parents=True, exist_ok=True)
        self._profiler.dump_stats(self._out_file)
