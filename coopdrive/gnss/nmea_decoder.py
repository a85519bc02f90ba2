"""NMEA 0183 byte stream -> GnssFix, one per receiver epoch (sentences sharing a UTC time).

GGA (or GNS) gives position and quality, GST the position sigmas, RMC/VTG speed and course, HDT/THS the true
heading of a dual-antenna receiver, RMC/ZDA the date. Sentences without a time of their own (VTG, HDT, THS)
join the epoch being assembled; a heading sent before its epoch's GGA (as Hemisphere receivers do) waits for it.
An epoch is emitted as soon as all of `expected_sentences` have arrived, or all the sentence types the
previous epoch had (the receiver's own layout, learned as it goes), else when the next epoch starts (or on
flush()). Bad sentences are counted by reason and skipped; a partial line waits for its end in the next chunk;
junk in front of a '$' is counted and the sentence after it still read.
"""

from __future__ import annotations

import datetime
import enum
from collections import Counter
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Callable

import pynmea2

from coopdrive.gnss import nmea_fields
from coopdrive.gnss.nmea_fields import (
    GGA_QUALITY_FIX_MODE, KMPH_TO_MPS, KNOTS_TO_MPS, MIN_FIELDS, POSITION_SENTENCES, TIMELESS, SentenceType,
)
from coopdrive.v1 import gnss_pb2

__all__ = ["BadSentence", "NmeaDecoder", "SentenceType", "nmea_checksum", "with_checksum", "KNOTS_TO_MPS",
           "KMPH_TO_MPS", "GGA_QUALITY_FIX_MODE", "DEFAULT_EXPECTED_SENTENCES"]

MAX_LINE_BYTES = 200  # NMEA allows 82 characters; proprietary sentences are longer but not this long
DEFAULT_EXPECTED_SENTENCES = frozenset({SentenceType.GGA, SentenceType.RMC, SentenceType.GST})
GAP_FACTOR = 1.5  # an epoch this many receiver intervals after the previous one follows a gap
DAY_S = 86400.0


class BadSentence(enum.Enum):
    NO_START = "no_start"  # line does not begin with '$'
    NO_CHECKSUM = "no_checksum"
    BAD_CHECKSUM = "bad_checksum"
    UNPARSABLE = "unparsable"
    TOO_LONG = "too_long"
    NOT_ASCII = "not_ascii"
    UNKNOWN_QUALITY = "unknown_quality"
    NO_TIME = "no_time"  # a sentence claiming a fix without a UTC time


def nmea_checksum(body: str) -> int:
    """XOR of the characters between '$' and '*' (NMEA 0183), as pynmea2 computes it."""
    return pynmea2.NMEASentence.checksum(body)


def with_checksum(body: str) -> str:
    """A full sentence for a body without '$' and checksum (for tests and the simulator)."""
    return f"${body}*{nmea_checksum(body):02X}"


@dataclass
class _Epoch:
    utc: datetime.time
    fix: gnss_pb2.GnssFix
    day_s: float  # seconds since midnight UTC
    opened_s: float  # arrival of its first sentence
    types: set[SentenceType] = field(default_factory=set)


class NmeaDecoder:
    def __init__(self, on_fix: Callable[[gnss_pb2.GnssFix], None],
                 expected_sentences: frozenset[SentenceType] = DEFAULT_EXPECTED_SENTENCES,
                 quality2_fix_mode: int = gnss_pb2.FIX_MODE_DGPS, receiver_latency_s: float = 0.0,
                 vehicle_id: str = "", sender: str = "geolocation") -> None:
        self._on_fix = on_fix
        self.expected_sentences = expected_sentences
        self._quality_map = {**GGA_QUALITY_FIX_MODE, 2: quality2_fix_mode}
        self.receiver_latency_s = receiver_latency_s
        self._vehicle_id = vehicle_id
        self._sender = sender
        self._buffer = b""
        self._epoch: _Epoch | None = None
        self._emitted_utc: datetime.time | None = None
        self._learned: frozenset[SentenceType] = frozenset()
        self._held: dict[SentenceType, pynmea2.NMEASentence] = {}
        self._date: datetime.date | None = None
        self._last_epoch_s: float | None = None
        self._interval_s: float | None = None
        self._sequence = 0
        self.bad: Counter[BadSentence] = Counter()
        self.sentences: Counter[SentenceType] = Counter()
        self.ignored = 0  # well-formed sentences of other types (GSA, GSV, proprietary, ...)
        self.late = 0  # epoch sentences arriving after the epoch was emitted
        self.no_fix = 0  # sentences saying the receiver has no fix (empty GGA quality 0, RMC V, ...)
        self.gaps = 0  # epochs that came more than GAP_FACTOR receiver intervals after the previous one
        self.largest_gap_s = 0.0

    def counts(self) -> dict[str, int]:
        """Diagnostics counters: bad sentences by reason, and what was not used and why."""
        counts = {f"nmea_bad_{reason.value}": n for reason, n in self.bad.items()}
        counts.update(nmea_ignored=self.ignored, nmea_late=self.late, nmea_no_fix=self.no_fix,
                      nmea_epoch_gaps=self.gaps, nmea_fixes=self._sequence)
        return counts

    def feed(self, data: bytes, receive_time_s: float) -> None:
        """Bytes as read from the serial port or socket, and when they were read (stack clock)."""
        self._buffer += data
        *lines, self._buffer = self._buffer.split(b"\n")
        if len(self._buffer) > MAX_LINE_BYTES:
            # A line that never ends (binary data on the port): keep a sentence start that may follow it.
            self.bad[BadSentence.TOO_LONG] += 1
            start = self._buffer.rfind(b"$")
            fits = 0 <= start and len(self._buffer) - start <= MAX_LINE_BYTES
            self._buffer = self._buffer[start:] if fits else b""
        for raw in lines:
            self._raw_line(raw.strip(b"\r\x00 "), receive_time_s)

    def flush(self) -> None:
        """Emit a pending epoch that lacks some expected sentence (e.g. at the end of a log)."""
        self._emit()

    def flush_stale(self, now_s: float, wait_s: float) -> None:
        """Emit an epoch with a position whose first sentence came wait_s ago or more: its other sentences are
        not coming (the receiver's first epoch, before its layout is known, or one that lacks a sentence)."""
        epoch = self._epoch
        if epoch is not None and epoch.types & POSITION_SENTENCES and now_s - epoch.opened_s >= wait_s:
            self._emit()

    def _raw_line(self, line: bytes, time_s: float) -> None:
        if not line:
            return
        # A lost line end or junk before a sentence: each '$' starts a sentence of its own.
        prefix, *sentences = line.split(b"$")
        if prefix.strip():
            self.bad[BadSentence.NO_START if prefix.isascii() else BadSentence.NOT_ASCII] += 1
        for sentence in sentences:
            self._line(b"$" + sentence, time_s)

    def _line(self, raw: bytes, time_s: float) -> None:
        try:
            line = raw.decode("ascii")
        except UnicodeDecodeError:
            self.bad[BadSentence.NOT_ASCII] += 1
            return
        reason = self._framing_error(line)
        if reason is not None:
            self.bad[reason] += 1
            return
        msg = self._parse(line)
        if msg is None:
            return
        try:
            sentence_type = SentenceType(msg.sentence_type)
        except (ValueError, AttributeError):
            self.ignored += 1
            return
        try:
            self._sentence(sentence_type, msg, time_s)
        except KeyError:
            self.bad[BadSentence.UNKNOWN_QUALITY] += 1
        except nmea_fields.Unusable:
            self.bad[BadSentence.NO_TIME] += 1
        except (ValueError, TypeError, AttributeError):
            self.bad[BadSentence.UNPARSABLE] += 1

    def _parse(self, line: str) -> pynmea2.NMEASentence | SimpleNamespace | None:
        body = line[1:].rpartition("*")[0]
        address = body.partition(",")[0]
        if len(address) == 5 and address.endswith("THS"):
            # pynmea2 has no THS: its fields are simply heading and mode.
            return SimpleNamespace(sentence_type="THS", data=body.split(",")[1:])
        try:
            return pynmea2.parse(line, check=False)
        except pynmea2.SentenceTypeError:
            self.ignored += 1  # well formed, of a type pynmea2 does not know (e.g. GLC)
        except (pynmea2.ParseError, ValueError):
            self.bad[BadSentence.UNPARSABLE] += 1
        return None

    @staticmethod
    def _framing_error(line: str) -> BadSentence | None:
        if len(line) > MAX_LINE_BYTES:
            return BadSentence.TOO_LONG
        if not line.startswith("$"):
            return BadSentence.NO_START
        body, star, checksum = line[1:].rpartition("*")
        if not star or len(checksum) != 2:
            return BadSentence.NO_CHECKSUM
        try:
            if int(checksum, 16) != nmea_checksum(body):
                return BadSentence.BAD_CHECKSUM
        except ValueError:
            return BadSentence.BAD_CHECKSUM
        return None

    def _sentence(self, sentence_type: SentenceType, msg, time_s: float) -> None:
        if len(msg.data) < MIN_FIELDS[sentence_type]:
            raise ValueError(f"{sentence_type.value} has {len(msg.data)} fields, needs {MIN_FIELDS[sentence_type]}")
        if sentence_type is SentenceType.ZDA:
            self._set_date(nmea_fields.date_of(sentence_type, msg))
            self.sentences[sentence_type] += 1
            return
        if sentence_type in TIMELESS:
            self._timeless(sentence_type, msg)
            return
        utc = nmea_fields.utc_time(msg)
        if utc is None:
            if nmea_fields.reports_no_fix(sentence_type, msg):
                self.no_fix += 1
                return
            raise nmea_fields.Unusable(f"{sentence_type.value} has no valid UTC time")
        self._set_date(nmea_fields.date_of(sentence_type, msg))
        if utc == self._emitted_utc:
            self.late += 1
            self._learned |= {sentence_type}
            return
        if self._epoch is None or utc != self._epoch.utc:
            self._open(utc, time_s)
        self._add(sentence_type, msg)

    def _timeless(self, sentence_type: SentenceType, msg) -> None:
        epoch = self._epoch
        if epoch is not None and sentence_type not in epoch.types:
            self._add(sentence_type, msg)
        elif sentence_type is not SentenceType.VTG:
            self._held[sentence_type] = msg  # a heading sent ahead of its epoch's GGA
        elif self._measures(sentence_type, msg):
            self.late += 1  # VTG follows its epoch: this one came after the epoch was emitted
            self._learned |= {sentence_type}
        else:
            self.no_fix += 1

    def _measures(self, sentence_type: SentenceType, msg) -> bool:
        scratch = gnss_pb2.GnssFix()
        self._fill(sentence_type, msg, scratch)
        return scratch.velocity_valid or scratch.heading_valid

    def _add(self, sentence_type: SentenceType, msg) -> None:
        epoch = self._epoch
        self._fill(sentence_type, msg, epoch.fix)
        epoch.types.add(sentence_type)
        self.sentences[sentence_type] += 1
        if not epoch.types & POSITION_SENTENCES:
            return
        if self.expected_sentences <= epoch.types or (self._learned and self._learned <= epoch.types):
            self._emit()

    def _fill(self, sentence_type: SentenceType, msg, fix: gnss_pb2.GnssFix) -> None:
        if sentence_type is SentenceType.GGA:
            nmea_fields.gga(msg, fix, self._quality_map)
        elif sentence_type is SentenceType.GNS:
            nmea_fields.gns(msg, fix)
        elif sentence_type is SentenceType.GST:
            nmea_fields.gst(msg, fix)
        elif sentence_type is SentenceType.RMC:
            nmea_fields.rmc(msg, fix)
        elif sentence_type is SentenceType.VTG:
            nmea_fields.vtg(msg, fix)
        else:
            nmea_fields.heading(sentence_type, msg, fix)

    def _set_date(self, date: datetime.date | None) -> None:
        if date is not None:
            self._date = date

    def _open(self, utc: datetime.time, time_s: float) -> None:
        self._emit()
        fix = gnss_pb2.GnssFix()
        fix.header.sample_time_s = time_s - self.receiver_latency_s
        day_s = utc.hour * 3600.0 + utc.minute * 60.0 + utc.second + utc.microsecond * 1e-6
        self._epoch = _Epoch(utc, fix, day_s, time_s)
        held, self._held = self._held, {}
        for sentence_type, msg in held.items():
            self._add(sentence_type, msg)

    def _utc_seconds(self, day_s: float) -> float:
        """Seconds since 1970 of an epoch (its date may come after its GGA, in the RMC), 0 while none is known."""
        if self._date is None:
            return 0.0
        midnight = datetime.datetime.combine(self._date, datetime.time(), tzinfo=datetime.timezone.utc)
        return midnight.timestamp() + day_s

    def _count_gap(self, day_s: float) -> None:
        """The receiver's interval is the shortest step between fixes; a step longer than GAP_FACTOR of it is
        a gap (the receiver lost its fix, or the port lost bytes)."""
        if self._last_epoch_s is not None:
            step_s = (day_s - self._last_epoch_s) % DAY_S  # across midnight too
            if 0.0 < step_s < DAY_S / 2.0:
                if self._interval_s is not None and step_s > GAP_FACTOR * self._interval_s:
                    self.gaps += 1
                    self.largest_gap_s = max(self.largest_gap_s, step_s)
                self._interval_s = step_s if self._interval_s is None else min(self._interval_s, step_s)
        self._last_epoch_s = day_s

    def _emit(self) -> None:
        epoch = self._epoch
        if epoch is None:
            return
        self._epoch = None
        if not epoch.types & POSITION_SENTENCES:
            return
        fix = epoch.fix
        fix.utc_time_s = self._utc_seconds(epoch.day_s)
        self._count_gap(epoch.day_s)
        self._sequence += 1
        fix.header.sequence = self._sequence
        fix.header.vehicle_id = self._vehicle_id
        fix.header.sender = self._sender
        self._emitted_utc = epoch.utc
        # Learn the receiver's epoch layout from epochs with a position (a no-fix epoch is often shorter).
        if fix.fix_mode != gnss_pb2.FIX_MODE_NO_FIX or not self._learned:
            self._learned = frozenset(epoch.types)
        self._on_fix(fix)
