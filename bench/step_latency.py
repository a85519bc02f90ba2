"""Clock-to-command latency of a lockstep run, seen from the launcher's hub: when world/clock for a step
arrived, and when the ego's actuation/command of that step arrived. Pass `observe` as RunOptions.observer.

The steps in which the ego's scene published (its 25 Hz update is then in the chain to the command) can be told
from the others: at 50 Hz they alternate, and the latency with them (docs/performance.md)."""

from __future__ import annotations

import threading
import time

import numpy as np


class StepLatency:
    def __init__(self) -> None:
        self._clock_arrivals: dict[float, float] = {}
        self._command_arrivals: dict[float, float] = {}
        # Step times at which the ego's scene was published.
        self._scene_steps: set[float] = set()
        self._lock = threading.Lock()

    def observe(self, key: str, message) -> None:
        now = time.perf_counter()
        with self._lock:
            if key.endswith("world/clock"):
                self._clock_arrivals[round(message.time_s, 6)] = now
            elif key.endswith("ego/actuation/command"):
                self._command_arrivals[round(message.header.sent_time_s, 6)] = now
            elif key.endswith("ego/scene"):
                self._scene_steps.add(round(message.header.sent_time_s, 6))

    def samples(self, scene_steps: bool | None = None) -> np.ndarray:
        """Per step whose clock and command both arrived: [clock arrival (perf_counter s), latency (ms)].
        scene_steps True: only the steps in which the scene published, False: only the others, None: all."""
        with self._lock:
            clock, command, scene = dict(self._clock_arrivals), dict(self._command_arrivals), set(self._scene_steps)
        rows = [(clock[t], 1e3 * (command[t] - clock[t])) for t in command
                if t in clock and command[t] >= clock[t] and (scene_steps is None or (t in scene) == scene_steps)]
        return np.array(rows).reshape(-1, 2)

    def latencies_ms(self, scene_steps: bool | None = None) -> np.ndarray:
        """The latency column of samples(scene_steps): the command's delay after the clock (ms)."""
        return self.samples(scene_steps)[:, 1]
