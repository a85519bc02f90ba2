"""Clock-to-command latency of a lockstep run, seen from the launcher's hub: when world/clock for a step
arrived, and when the ego's actuation/command of that step arrived. Pass `observe` as RunOptions.observer."""

from __future__ import annotations

import threading
import time

import numpy as np


class StepLatency:
    def __init__(self) -> None:
        self._clock_arrivals: dict[float, float] = {}
        self._command_arrivals: dict[float, float] = {}
        self._lock = threading.Lock()

    def observe(self, key: str, message) -> None:
        now = time.perf_counter()
        with self._lock:
            if key.endswith("world/clock"):
                self._clock_arrivals[round(message.time_s, 6)] = now
            elif key.endswith("ego/actuation/command"):
                self._command_arrivals[round(message.header.sent_time_s, 6)] = now

    def samples(self) -> np.ndarray:
        """Per step whose clock and command both arrived: [clock arrival (perf_counter s), latency (ms)]."""
        with self._lock:
            clock, command = dict(self._clock_arrivals), dict(self._command_arrivals)
        rows = [(clock[t], 1e3 * (command[t] - clock[t])) for t in command if t in clock and command[t] >= clock[t]]
        return np.array(rows).reshape(-1, 2)

    def latencies_ms(self) -> np.ndarray:
        """Per step whose clock and command both arrived, the command's delay after the clock (ms)."""
        with self._lock:
            clock, command = dict(self._clock_arrivals), dict(self._command_arrivals)
        return np.array([1e3 * (command[t] - clock[t]) for t in command if t in clock and command[t] >= clock[t]])
