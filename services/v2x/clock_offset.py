"""How far a station's clock is from ours, read off its messages' generation times, and what that likely means.

A CAM's generation time is the sender's TimestampIts: TAI milliseconds since 2004 (TS 102 894-2). A station
whose generation times run a steady few seconds off ours is not late, its clock is: a whole number of seconds is the
sign of a time scale mixed up (UTC counted without the leap seconds since 2004, or GPS time), where a drifting
fraction is a clock not synchronised. Its messages then look too old or from the future, and are refused as such.
"""

from __future__ import annotations

import statistics
from collections import deque

from coopdrive.v2x.timebase import MS_PER_S

# Offsets the median is taken over: a handful of messages, so one late packet does not move it.
OFFSET_SAMPLES = 16
# Below this the offset is transit and jitter, not a clock.
CLOCK_OFFSET_NOTICED_S = 0.5
# How close to a whole number of seconds an offset must be to be called one.
WHOLE_SECONDS_TOLERANCE_S = 0.1
# GPS time runs this far behind TAI at all times.
TAI_MINUS_GPS_S = 19


class ClockOffset:
    """The median of a station's last generation-time offsets (its time minus our receive time), in seconds."""

    def __init__(self, samples: int = OFFSET_SAMPLES):
        self._offsets_s: deque[float] = deque(maxlen=samples)

    def add(self, generation_tai_ms: int, receive_tai_ms: int) -> None:
        self._offsets_s.append((generation_tai_ms - receive_tai_ms) / MS_PER_S)

    def offset_s(self) -> float | None:
        return statistics.median(self._offsets_s) if self._offsets_s else None

    def is_off(self) -> bool:
        """More than transit and jitter apart."""
        offset_s = self.offset_s()
        return offset_s is not None and abs(offset_s) >= CLOCK_OFFSET_NOTICED_S


def diagnose(offset_s: float, leap_seconds_since_2004: int) -> str:
    """A likely cause for a station clock offset_s from ours (negative: behind), or "" when it is within transit."""
    if abs(offset_s) < CLOCK_OFFSET_NOTICED_S:
        return ""
    whole_s = round(offset_s)
    direction = "behind" if offset_s < 0 else "ahead of"
    if abs(offset_s - whole_s) > WHOLE_SECONDS_TOLERANCE_S:
        return f"its clock is {abs(offset_s):.1f} s {direction} ours: not synchronised"
    causes = {-leap_seconds_since_2004: f"it stamps UTC since 2004 without the {leap_seconds_since_2004} leap "
                                        "seconds since (TimestampIts is TAI, TS 102 894-2)",
              -TAI_MINUS_GPS_S: f"it stamps GPS time, which runs {TAI_MINUS_GPS_S} s behind TAI"}
    cause = causes.get(whole_s, "a whole number of seconds: likely another time scale than TAI (UTC, GPS)")
    return f"its clock is {abs(whole_s)} s {direction} ours: {cause}"
