"""A line on a terminal that says how far a run has got in simulated time, redrawn in place a few times a second."""

from __future__ import annotations

import sys
import threading
import time
from typing import TextIO

# Redrawn at most this often: the clock ticks every step (50 times a simulated second).
REDRAW_PERIOD_S = 0.25


class ProgressLine:
    """Fed the simulator's clock from the bus's thread; draws only on a terminal, so logs and pipes stay clean."""

    def __init__(self, stream: TextIO = sys.stderr):
        self._stream = stream
        self._enabled = stream.isatty()
        self._lock = threading.Lock()
        self._drawn_at_s = float("-inf")
        self._width = 0

    def update(self, sim_time_s: float, duration_s: float) -> None:
        if not self._enabled:
            return
        now = time.monotonic()
        with self._lock:
            if now - self._drawn_at_s < REDRAW_PERIOD_S and sim_time_s < duration_s:
                return
            self._drawn_at_s = now
            text = f"simulated {sim_time_s:.1f} of {duration_s:.1f} s"
            self._width = max(self._width, len(text))
            self._stream.write(f"\r{text:<{self._width}}")
            self._stream.flush()

    def close(self) -> None:
        """Clears the line, so what is printed next starts on a clean one."""
        with self._lock:
            if self._enabled and self._width:
                self._stream.write(f"\r{' ' * self._width}\r")
                self._stream.flush()
            self._enabled = False
