"""The benchmarks' baseline layout: runs started inside `thread_per_service(True)` give each service of a vehicle's
group its own thread, as before the shared worker (coopdrive/runtime/group.py); the launched processes inherit it."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

from coopdrive.runtime.group import THREAD_PER_SERVICE_VARIABLE


@contextmanager
def thread_per_service(enabled: bool) -> Iterator[None]:
    os.environ[THREAD_PER_SERVICE_VARIABLE] = "1" if enabled else "0"
    try:
        yield
    finally:
        del os.environ[THREAD_PER_SERVICE_VARIABLE]
