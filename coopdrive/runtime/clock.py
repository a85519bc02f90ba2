"""Clocks: wall time on the vehicle, simulation time in the simulator."""

import time


class WallClock:
    """Seconds since the Unix epoch, so timestamps compare across hosts synchronised by NTP/PTP."""

    def now_s(self) -> float:
        return time.time()


class SimulationClock:
    """Follows the simulator's clock messages; time stands still between them."""

    def __init__(self) -> None:
        self._time_s = 0.0

    def set(self, time_s: float) -> None:
        self._time_s = time_s

    def now_s(self) -> float:
        return self._time_s
