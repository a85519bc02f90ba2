"""How often a remote station is expected to send a periodic stream (its CAMs, its iCLCMs, a roadside unit's
SPATEMs), so that a gap in its generation times can be counted in missed messages, or its silence told from its
pace.

- A fixed rate, where a profile sets one: GCDC 2016 sent every CAM and iCLCM at 25 Hz.
- Otherwise the station's own: EN 302 637-2 (6.1.3) lets a CAM come every 100 to 1000 ms as the vehicle's dynamics
  trigger it, so no single rate fits every station or every moment. The expected period is then the median of the
  station's last generation gaps: a message lost now and then makes a gap twice as long without moving the median.
"""

from __future__ import annotations

import statistics
from collections import deque

from coopdrive.v2x.timebase import MS_PER_S

# Gaps the observed period is the median of: enough to ride over a loss, few enough to follow a change of rate
# (a station that slows from 10 Hz to 1 Hz is followed after about 5 of its slow gaps).
OBSERVED_GAPS = 8


class ExpectedPeriod:
    """A stream's expected generation period; None while it cannot be told yet."""

    def period_ms(self) -> float | None:
        raise NotImplementedError

    def observe(self, gap_ms: float) -> None:
        """One more gap between two generation times of the stream."""


class FixedPeriod(ExpectedPeriod):
    def __init__(self, rate_hz: float):
        self._period_ms = MS_PER_S / rate_hz

    def period_ms(self) -> float:
        return self._period_ms


class ObservedPeriod(ExpectedPeriod):
    def __init__(self, gaps: int = OBSERVED_GAPS):
        self._gaps: deque[float] = deque(maxlen=gaps)

    def period_ms(self) -> float | None:
        return statistics.median(self._gaps) if self._gaps else None

    def observe(self, gap_ms: float) -> None:
        if gap_ms > 0:
            self._gaps.append(gap_ms)


def expected_period(rate_hz: float | None) -> ExpectedPeriod:
    """The fixed rate where one is given, else the station's own."""
    return FixedPeriod(rate_hz) if rate_hz is not None else ObservedPeriod()
