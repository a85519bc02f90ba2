"""Waiting for hardware: a deployed service whose device (serial port, CAN interface) cannot be opened yet says so
once and tries again, instead of exiting into its container's restart loop.

On a vehicle the USB receiver may enumerate after the container starts, a CAN interface come up later; on a
laptop without the car the service just waits, visibly not alive, until stopped.
"""

from __future__ import annotations

import signal
import sys
import threading
from typing import Callable, Protocol

from coopdrive.runtime.service import HardwareUnavailable
from coopdrive.runtime.signal_wait import wait_hearing_signals


class Runner(Protocol):
    stopping: bool

    def run(self) -> str: ...


def run_waiting_for_hardware(make_runner: Callable[[], Runner], retry_s: float | None, name: str) -> None:
    """Runs a new runner until one ends without HardwareUnavailable; between attempts waits retry_s (None: raise
    at once). One line on stderr per distinct reason; SIGINT or SIGTERM at any time (waiting, or while an attempt
    was opening its device) ends it: a clean stop."""
    stop = threading.Event()
    announced = None
    while True:
        _stop_on_signals(stop)  # each attempt's runner installs its own handlers while it runs
        runner = None
        try:
            runner = make_runner()
            runner.run()
            return
        except HardwareUnavailable as error:
            if retry_s is None:
                raise
            if stop.is_set() or (runner is not None and runner.stopping):
                return
            if str(error) != announced:
                announced = str(error)
                print(f"coopdrive: {name}: {error}; trying again every {retry_s:g} s", file=sys.stderr, flush=True)
        _stop_on_signals(stop)
        if wait_hearing_signals(stop, retry_s):
            return


def _stop_on_signals(stop: threading.Event) -> None:
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, lambda *_: stop.set())
