"""Waiting on the main thread of a process with native threads (Zenoh's), so that SIGINT and SIGTERM are heard.

CPython runs a signal's Python handler on the main thread, between bytecodes. The kernel may deliver the signal
to any thread that does not block it, Zenoh's native ones included; the main thread is then not interrupted, and
one blocked in Event.wait() without a timeout never comes back to run the handler. `coopdrive record` ignored
Ctrl-C that way in 1 of 8 tries while a peer's session was going. Waiting in slices of SIGNAL_POLL_S looks at
pending handlers at least that often.
"""

from __future__ import annotations

import threading
import time

# How long a signal may wait for the main thread to look: well below a container's 10 s stop grace.
SIGNAL_POLL_S = 0.1


def wait_hearing_signals(event: threading.Event, timeout_s: float | None = None) -> bool:
    """event.wait(timeout_s), with the main thread free to run signal handlers every SIGNAL_POLL_S."""
    deadline_s = None if timeout_s is None else time.monotonic() + timeout_s
    while True:
        slice_s = SIGNAL_POLL_S if deadline_s is None else min(SIGNAL_POLL_S, deadline_s - time.monotonic())
        if slice_s <= 0.0:
            return event.is_set()
        if event.wait(slice_s):
            return True


def join_hearing_signals(threads: list[threading.Thread]) -> None:
    """Each thread's join, with the main thread free to run signal handlers every SIGNAL_POLL_S."""
    for thread in threads:
        while thread.is_alive():
            thread.join(SIGNAL_POLL_S)
