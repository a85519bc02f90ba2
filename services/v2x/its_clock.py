"""The service clock as ITS time: the clock plus a configured epoch is UTC, UTC gives TimestampIts (TAI ms).

On a vehicle the clock is unix time and the epoch is 0; in simulation the clock starts at 0 and the epoch is
the UTC instant the scenario pretends to start at.
"""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.services.v2x.timebase import MS_PER_S, tai_ms_from_unix_s, unix_s_from_tai_ms


@dataclass(frozen=True)
class ItsClock:
    epoch_unix_s: float = 0.0

    def unix_s(self, clock_s: float) -> float:
        return clock_s + self.epoch_unix_s

    def tai_ms(self, clock_s: float) -> int:
        return tai_ms_from_unix_s(self.unix_s(clock_s))

    def clock_s_of_tai(self, tai_ms: int) -> float:
        return unix_s_from_tai_ms(tai_ms) - self.epoch_unix_s

    @staticmethod
    def seconds_between(earlier_tai_ms: int, later_tai_ms: int) -> float:
        return (later_tai_ms - earlier_tai_ms) / MS_PER_S
