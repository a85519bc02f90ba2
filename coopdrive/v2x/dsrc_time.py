"""The DSRC messages' time base (ISO TS 19091 / SAE J2735, as TS 103 301 uses it): a TimeMark counts tenths of a
second from the start of the current UTC hour, a SPATEM's own stamp is MinuteOfTheYear with DSecond in that
minute. The roadside unit that writes them and the planner that reads them share these."""

from __future__ import annotations

import calendar

SECONDS_PER_HOUR = 3600.0
SECONDS_PER_MINUTE = 60.0


def unix_s_of_minute_of_year(year: int, minute_of_year: int, second_of_minute_s: float) -> float:
    """A SPATEM's own time stamp (MinuteOfTheYear, DSecond) as unix time, in the year given."""
    return calendar.timegm((year, 1, 1, 0, 0, 0)) + minute_of_year * SECONDS_PER_MINUTE + second_of_minute_s
