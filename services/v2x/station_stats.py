"""Reception statistics of one remote station over a sliding window.

- message rate: accepted messages per second of the station's busiest stream (its CAMs at GCDC);
- reception ratio: received / expected messages of its periodic streams (CAM, iCLCM), where the expected
  count comes from the generationDeltaTime gaps at the stream's expected period (expected_period.py: a profile's
  fixed rate, a 120 ms gap at 25 Hz = 3 slots, 2 lost; or the station's own median gap);
- update delay: receive time - generation time, p50 / p95 / max;
- LOST once nothing was heard for the loss timeout (400 ms at GCDC);
- security: how many of its packets were signed, verified, trusted, had an invalid signature or were refused
  by the security mode, and why the last one fell short.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from coopdrive.services.v2x.clock_offset import ClockOffset, diagnose
from coopdrive.v2x.expected_period import ExpectedPeriod, expected_period
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.security_verdict import SecurityVerdict
from coopdrive.v2x.timebase import MS_PER_S
from coopdrive.v1 import v2x_pb2

PERIODIC_TYPES = (ItsMessageId.CAM, ItsMessageId.ICLCM)
# A station is lost after this many of its own CAM periods without a word, where that is longer than the setting.
LOST_AFTER_MISSED_CAMS = 3


class StreamWindow:
    """One message type of one station: (receive time, slots the message closes) in the window."""

    def __init__(self, expected: ExpectedPeriod, window_s: float):
        self.expected = expected
        self.window_s = window_s
        self._entries: deque[tuple[float, int]] = deque()
        # The slots of the entries in the window, kept as they come and go (a status asks for it twice a second).
        self._slots_in_window = 0
        self._last_generation_tai_ms: int | None = None
        # Since the first message, not only in the window.
        self.received_total = 0
        self.expected_total = 0

    def add(self, receive_s: float, generation_tai_ms: int | None) -> None:
        slots = 1
        if generation_tai_ms is not None and self._last_generation_tai_ms is not None:
            gap_ms = generation_tai_ms - self._last_generation_tai_ms
            period_ms = self.expected.period_ms()
            if period_ms is not None:
                # Cap: a silence longer than the window says nothing about the window.
                max_slots = max(1, round(self.window_s * MS_PER_S / period_ms))
                slots = min(max(1, round(gap_ms / period_ms)), max_slots)
            self.expected.observe(gap_ms)
        if generation_tai_ms is not None:
            self._last_generation_tai_ms = generation_tai_ms
        self._entries.append((receive_s, slots))
        self._slots_in_window += slots
        self.received_total += 1
        self.expected_total += slots
        self.prune(receive_s)

    def prune(self, now_s: float) -> None:
        while self._entries and self._entries[0][0] < now_s - self.window_s:
            self._slots_in_window -= self._entries.popleft()[1]

    def received_and_expected(self) -> tuple[int, int]:
        # The first message of the window closes a gap that started before it: count it as one slot.
        expected = self._slots_in_window - (self._entries[0][1] - 1 if self._entries else 0)
        return len(self._entries), expected

    def rate_hz(self, now_s: float, first_heard_s: float) -> float:
        span_s = min(self.window_s, now_s - first_heard_s)
        if span_s <= 0:
            return 0.0
        return len(self._entries) / span_s


class StationSecurity:
    """Counts of one station's security verdicts, delivered and refused packets alike."""

    def __init__(self) -> None:
        self.last: SecurityVerdict | None = None
        self.signed = self.verified = self.trusted = self.untrusted = self.signature_failures = self.refused = 0
        self.last_reason = ""

    def add(self, verdict: SecurityVerdict, refused: bool) -> None:
        self.last = verdict
        self.signed += int(verdict.signed)
        self.verified += int(verdict.verified is True)
        self.trusted += int(verdict.trusted is True)
        self.untrusted += int(verdict.trusted is False)
        self.signature_failures += int(verdict.verified is False)
        self.refused += int(refused)
        if verdict.reason is not None:
            self.last_reason = verdict.reason
        elif verdict.verified and verdict.trusted:
            self.last_reason = ""

    def fill(self, stats: v2x_pb2.StationLinkStats) -> None:
        last = self.last
        if last is not None:
            stats.signed, stats.verified, stats.trusted = last.signed, last.verified is True, last.trusted is True
        stats.messages_signed, stats.messages_verified = self.signed, self.verified
        stats.messages_trusted, stats.messages_untrusted = self.trusted, self.untrusted
        stats.signature_failures, stats.messages_refused_by_security = self.signature_failures, self.refused
        stats.last_security_reason = self.last_reason


class StationStats:
    def __init__(self, station_id: int, expected_rate_hz: float | None, window_s: float):
        """expected_rate_hz: every periodic stream's rate (a profile's, GCDC's 25 Hz); None: each stream's own."""
        self.station_id = station_id
        self.expected_rate_hz = expected_rate_hz
        self.window_s = window_s
        self.first_heard_s: float | None = None
        self.last_heard_s: float | None = None
        # Last packet of any kind, accepted or not: when the station may be forgotten.
        self.last_seen_s: float | None = None
        self.messages_received = 0
        self.messages_rejected = 0
        self._streams: dict[ItsMessageId, StreamWindow] = {}
        self._delays: deque[tuple[float, float]] = deque()
        self.security = StationSecurity()
        self.clock = ClockOffset()

    def on_message(self, message_type: ItsMessageId, receive_s: float, generation_tai_ms: int | None,
                   delay_s: float | None) -> None:
        if self.first_heard_s is None:
            self.first_heard_s = receive_s
        self.last_heard_s = self.last_seen_s = receive_s
        self.messages_received += 1
        stream = self._streams.get(message_type)
        if stream is None:
            stream = self._streams[message_type] = StreamWindow(expected_period(self.expected_rate_hz), self.window_s)
        stream.add(receive_s, generation_tai_ms if message_type in PERIODIC_TYPES else None)
        if delay_s is not None:
            self._delays.append((receive_s, delay_s))

    def on_rejected(self, receive_s: float) -> None:
        self.last_seen_s = receive_s
        self.messages_rejected += 1

    def is_lost(self, now_s: float, loss_timeout_s: float) -> bool:
        """Not heard for loss_timeout_s, or for LOST_AFTER_MISSED_CAMS of its own CAM periods where that is longer:
        a standard station sends a CAM every 100-1000 ms (EN 302 637-2 6.1.3), and one heard every 400 ms is
        not lost between two CAMs. At GCDC's 25 Hz the setting decides (0.4 s against 3 periods of 40 ms)."""
        if self.last_heard_s is None:
            return True
        cam_period_ms = self._cam_period_ms()
        if cam_period_ms:
            loss_timeout_s = max(loss_timeout_s, LOST_AFTER_MISSED_CAMS * cam_period_ms / MS_PER_S)
        return now_s - self.last_heard_s > loss_timeout_s

    def _cam_period_ms(self) -> float | None:
        """The period its CAMs are expected at (the profile's, or as measured), None before its first CAM."""
        cam_stream = self._streams.get(ItsMessageId.CAM)
        return cam_stream.expected.period_ms() if cam_stream is not None else None

    def reception_ratio(self, now_s: float) -> float:
        received = expected = 0
        for message_type, stream in self._streams.items():
            if message_type in PERIODIC_TYPES:
                stream.prune(now_s)
                got, wanted = stream.received_and_expected()
                received, expected = received + got, expected + wanted
        return received / expected if expected else 0.0

    def periodic_totals(self) -> tuple[int, int]:
        """(received, expected) of the periodic streams since the station was first heard."""
        periodic = [stream for message_type, stream in self._streams.items() if message_type in PERIODIC_TYPES]
        return sum(s.received_total for s in periodic), sum(s.expected_total for s in periodic)

    def to_proto(self, now_s: float, loss_timeout_s: float, leap_seconds: int = 0) -> v2x_pb2.StationLinkStats:
        """leap_seconds: since 2004 at now_s, to name a clock offset of that many seconds."""
        for stream in self._streams.values():
            stream.prune(now_s)
        while self._delays and self._delays[0][0] < now_s - self.window_s:
            self._delays.popleft()
        stats = v2x_pb2.StationLinkStats(
            station_id=self.station_id,
            state=v2x_pb2.LINK_STATE_LOST if self.is_lost(now_s, loss_timeout_s) else v2x_pb2.LINK_STATE_ACTIVE,
            last_heard_s=self.last_heard_s or 0.0, reception_ratio=self.reception_ratio(now_s),
            messages_received=self.messages_received, messages_rejected=self.messages_rejected)
        stats.periodic_received_total, stats.periodic_expected_total = self.periodic_totals()
        cam_period_ms = self._cam_period_ms()
        if cam_period_ms:
            stats.expected_cam_rate_hz = MS_PER_S / cam_period_ms
        offset_s = self.clock.offset_s()
        if offset_s is not None:
            stats.clock_offset_s, stats.clock_diagnostic = offset_s, diagnose(offset_s, leap_seconds)
        self.security.fill(stats)
        if self.first_heard_s is not None and self._streams:
            stats.message_rate_hz = max(stream.rate_hz(now_s, self.first_heard_s) for stream in self._streams.values())
        if self._delays:
            delays = np.array([delay for _, delay in self._delays])
            stats.update_delay_p50_s, stats.update_delay_p95_s = (float(v) for v in np.percentile(delays, [50, 95]))
            stats.update_delay_max_s = float(delays.max())
        return stats
