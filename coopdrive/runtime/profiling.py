"""WorkerProfile: a service worker's own cProfile, for finding where a run's time goes (docs/performance.md).

Set COOPDRIVE_PROFILE_DIR and every service worker, in every process of a run, writes
<dir>/<vehicle>-<service>.prof when it stops (read it with `python -m pstats` or snakeviz); a group in simulated
time, whose services share one worker (shared_worker.py), writes <dir>/<vehicle>-group.prof. Only the worker's
thread is profiled (handlers, triggers, lockstep), not Zenoh's threads, and start-up is left out.
"""

from __future__ import annotations

import cProfile
import os
from pathlib import Path

PROFILE_DIR_VARIABLE = "COOPDRIVE_PROFILE_DIR"


class WorkerProfile:
    def __init__(self, out_file: Path | None):
        self._out_file = out_file
        self._profiler = cProfile.Profile() if out_file is not None else None

    @classmethod
    def from_environment(cls, name: str) -> WorkerProfile:
        folder = os.environ.get(PROFILE_DIR_VARIABLE)
        return cls(Path(folder) / f"{name}.prof" if folder else None)

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
