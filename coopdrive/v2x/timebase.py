"""ITS time: TAI milliseconds since 2004-01-01T00:00:00Z (TimestampIts), generationDeltaTime, and the service
clock as ITS time (ItsClock).

TimestampIts counts TAI milliseconds since the 2004 epoch; unix time counts UTC seconds without leap
seconds, so leap seconds inserted after 2004 are added back from the table below.
"""

from __future__ import annotations

import bisect
import calendar
from dataclasses import dataclass
from datetime import datetime, timezone

MS_PER_S = 1000
US_PER_MS = 1000
US_PER_S = 1_000_000
GENERATION_DELTA_TIME_MODULUS = 65_536
UNIX_S_AT_ITS_EPOCH = calendar.timegm((2004, 1, 1, 0, 0, 0))
TAI_MINUS_UTC_AT_ITS_EPOCH_S = 32

# (unix time from which it applies, TAI - UTC in s), IERS Bulletin C; update when a leap second is announced.
LEAP_SECONDS = (
    (calendar.timegm((2006, 1, 1, 0, 0, 0)), 33),
    (calendar.timegm((2009, 1, 1, 0, 0, 0)), 34),
    (calendar.timegm((2012, 7, 1, 0, 0, 0)), 35),
    (calendar.timegm((2015, 7, 1, 0, 0, 0)), 36),
    (calendar.timegm((2017, 1, 1, 0, 0, 0)), 37),
)
_LEAP_STARTS_UNIX_S = [start for start, _ in LEAP_SECONDS]


def leap_seconds_since_its_epoch(unix_s: float) -> int:
    index = bisect.bisect_right(_LEAP_STARTS_UNIX_S, unix_s)
    tai_minus_utc_s = LEAP_SECONDS[index - 1][1] if index else TAI_MINUS_UTC_AT_ITS_EPOCH_S
    return tai_minus_utc_s - TAI_MINUS_UTC_AT_ITS_EPOCH_S


def tai_ms_from_unix_s(unix_s: float) -> int:
    """TimestampIts of a unix (UTC) time."""
    return round((unix_s - UNIX_S_AT_ITS_EPOCH + leap_seconds_since_its_epoch(unix_s)) * MS_PER_S)


def tai_ms_from_utc(utc: datetime) -> int:
    if utc.tzinfo is None:
        raise ValueError("utc must be timezone-aware")
    return tai_ms_from_unix_s(utc.astimezone(timezone.utc).timestamp())


def unix_s_from_tai_ms(tai_ms: int) -> float:
    """Inverse of tai_ms_from_unix_s (times inside a leap second map to the second after it)."""
    approximate_unix_s = tai_ms / MS_PER_S + UNIX_S_AT_ITS_EPOCH
    leap_s = leap_seconds_since_its_epoch(approximate_unix_s)
    unix_s = approximate_unix_s - leap_s
    if leap_seconds_since_its_epoch(unix_s) != leap_s:
        unix_s = approximate_unix_s - leap_seconds_since_its_epoch(unix_s)
    return unix_s


def generation_delta_time_ms(tai_ms: int) -> int:
    """generationDeltaTime = TimestampIts mod 65536 (EN 302 637-2)."""
    return tai_ms % GENERATION_DELTA_TIME_MODULUS


def tai_ms_from_delta(delta_ms: int, reference_tai_ms: int) -> int:
    """The TimestampIts nearest to reference_tai_ms whose generationDeltaTime is delta_ms.

    Unambiguous while the message is less than 32.768 s away from the reference (the receive time).
    """
    offset = (delta_ms - reference_tai_ms) % GENERATION_DELTA_TIME_MODULUS
    if offset >= GENERATION_DELTA_TIME_MODULUS // 2:
        offset -= GENERATION_DELTA_TIME_MODULUS
    return reference_tai_ms + offset


@dataclass(frozen=True)
class ItsClock:
    """The service clock as ITS time: the clock plus a configured epoch is UTC, UTC gives TimestampIts.

    On a vehicle the clock is unix time and the epoch is 0; in simulation the clock starts at 0 and the epoch
    is the UTC instant the scenario pretends to start at.
    """

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
