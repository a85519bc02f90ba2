"""The benchmarks' baselines, switched on for the runs started inside them (the launched processes inherit the
environment; each switch is read when a group or a bus starts, so forked services see it too):

- `thread_per_service(True)`: each service of a vehicle's group on its own thread, as before the shared worker
  (coopdrive/runtime/group.py);
- `local_by_zenoh(True)`: a session's own subscribers get its puts through Zenoh, as before the bus delivered
  them itself (coopdrive/bus/local_delivery.py).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

from coopdrive.bus.session import LOCAL_BY_ZENOH_VARIABLE
from coopdrive.runtime.group import THREAD_PER_SERVICE_VARIABLE


@contextmanager
def _switched(variable: str, enabled: bool) -> Iterator[None]:
    os.environ[variable] = "1" if enabled else "0"
    try:
        yield
    finally:
        del os.environ[variable]


def thread_per_service(enabled: bool):
    return _switched(THREAD_PER_SERVICE_VARIABLE, enabled)


def local_by_zenoh(enabled: bool):
    return _switched(LOCAL_BY_ZENOH_VARIABLE, enabled)
