"""SPaT times on the stack clock. A TimeMark counts tenths of a second from the start of the current UTC hour
(ISO TS 19091 / SAE J2735 DE_TimeMark; 36001 unknown, absent in our protobuf): which hour is meant is the one that
puts it nearest the receiver's UTC, so a mark just past the hour read just before it (or the reverse) lands in
the next (the previous) hour."""

from __future__ import annotations

import math

from coopdrive.v2x.dsrc_time import SECONDS_PER_HOUR
from coopdrive.v2x.timebase import ItsClock


def stack_time_of_mark_s(mark_s: float, now_s: float, clock: ItsClock) -> float:
    """The stack time of a TimeMark (seconds after its hour began) read at stack time now_s."""
    unix_now_s = clock.unix_s(now_s)
    hour_start_s = math.floor(unix_now_s / SECONDS_PER_HOUR) * SECONDS_PER_HOUR
    candidate_s = hour_start_s + mark_s
    offset_s = math.remainder(candidate_s - unix_now_s, SECONDS_PER_HOUR)
    return now_s + offset_s

