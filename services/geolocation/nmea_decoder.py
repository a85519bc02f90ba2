"""NMEA 0183 byte stream -> GnssFix, one per receiver epoch (sentences sharing a UTC time).

GGA gives position and quality, GST the position sigmas, RMC/VTG speed and course. An epoch is emitted as
soon as all of `expected_sentences` have arrived, else when the next epoch starts (or on flush()).
Bad sentences are counted by reason and skipped; a partial line waits for its end in the next chunk.
"""

from __future__ import annotations

import datetime
import enum
from collections import Counter
from typing import Callable

import pynmea2

from coopdrive.v1 import gnss_pb2

KNOTS_TO_MPS = 1852.0 / 3600.0
KMPH_TO_MPS = 1.0 / 3.6
MAX_LINE_BYTES = 200  # NMEA allows 82 characters; proprietary sentences are longer but not this long

# GGA quality indicator -> fix mode. Quality 2 is DGPS for NovAtel but includes SBAS on u-blox receivers:
# the decoder's quality2_fix_mode says which (Heudiasyc Table 1 tells PSRDIFF from SBAS).
GGA_QUALITY_FIX_MODE = {
    0: gnss_pb2.FIX_MODE_NO_FIX,
    1: gnss_pb2.FIX_MODE_SINGLE,
    2: gnss_pb2.FIX_MODE_DGPS,
    4: gnss_pb2.FIX_MODE_RTK_FIXED,
    5: gnss_pb2.FIX_MODE_RTK_FLOAT,
    6: gnss_pb2.FIX_MODE_NO_FIX,  # dead reckoning inside the receiver: not a measurement
    7: gnss_pb2.FIX_MODE_NO_FIX,  # manual input
    8: gnss_pb2.FIX_MODE_NO_FIX,  # simulator
    9: gnss_pb2.FIX_MODE_SBAS,  # NovAtel WAAS/EGNOS
}


class BadSentence(enum.Enum):
    NO_START = "no_start"  # line does not begin with '$'
    NO_CHECKSUM = "no_checksum"
    BAD_CHECKSUM = "bad_checksum"
    UNPARSABLE = "unparsable"
    TOO_LONG = "too_long"
    NOT_ASCII = "not_ascii"
    UNKNOWN_QUALITY = "unknown_quality"


class SentenceType(enum.Enum):
    GGA = "GGA"
    RMC = "RMC"
    GST = "GST"
    VTG = "VTG"


# Fields a sentence must carry to be used (pynmea2 accepts short sentences and leaves fields missing).
MIN_FIELDS = {SentenceType.GGA: 10, SentenceType.RMC: 8, SentenceType.GST: 8, SentenceType.VTG: 8}


def nmea_checksum(body: str) -> int:
    """XOR of the characters between '$' and '*'."""
    value = 0
    for char in body:
        value ^= ord(char)
    return value


def with_checksum(body: str) -> str:
    """A full sentence for a body without '$' and checksum (for tests and the simulator)."""
    return f"${body}*{nmea_checksum(body):02X}"


class NmeaDecoder:
    def __init__(self, on_fix: Callable[[gnss_pb2.GnssFix], None],
                 expected_sentences: frozenset[SentenceType] = frozenset(
                     {SentenceType.GGA, SentenceType.RMC, SentenceType.GST}),
                 quality2_fix_mode: int = gnss_pb2.FIX_MODE_DGPS, receiver_latency_s: float = 0.0,
                 vehicle_id: str = "", sender: str = "geolocation") -> None:
        self._on_fix = on_fix
        self.expected_sentences = expected_sentences
        self._quality_map = {**GGA_QUALITY_FIX_MODE, 2: quality2_fix_mode}
        self.receiver_latency_s = receiver_latency_s
        self._vehicle_id = vehicle_id
        self._sender = sender
        self._buffer = b""
        self._epoch_utc: datetime.time | None = None
        self._epoch_types: set[SentenceType] = set()
        self._epoch_fix: gnss_pb2.GnssFix | None = None
        self._emitted_utc: datetime.time | None = None
        self._sequence = 0
        self.bad: Counter[BadSentence] = Counter()
        self.sentences: Counter[SentenceType] = Counter()
        self.ignored = 0  # well-formed sentences of other types (GSA, GSV, ...)
        self.late = 0  # epoch sentences arriving after the epoch was emitted

    def feed(self, data: bytes, receive_time_s: float) -> None:
        """Bytes as read from the serial port or socket, and when they were read (stack clock)."""
        self._buffer += data
        *lines, self._buffer = self._buffer.split(b"\n")
        if len(self._buffer) > MAX_LINE_BYTES:
            self.bad[BadSentence.TOO_LONG] += 1
            self._buffer = b""
        for raw in lines:
            line = raw.strip(b"\r\x00 ")
            if line:
                self._line(line, receive_time_s)

    def flush(self) -> None:
        """Emit a pending epoch that lacks some expected sentence (e.g. at the end of a log)."""
        self._emit()

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
        try:
            msg = pynmea2.parse(line, check=False)
        except (pynmea2.ParseError, ValueError):
            self.bad[BadSentence.UNPARSABLE] += 1
            return
        try:
            sentence_type = SentenceType(msg.sentence_type)
        except (ValueError, AttributeError):
            self.ignored += 1
            return
        try:
            self._sentence(sentence_type, msg, time_s)
        except (ValueError, TypeError, AttributeError):
            self.bad[BadSentence.UNPARSABLE] += 1

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

    def _sentence(self, sentence_type: SentenceType, msg: pynmea2.NMEASentence, time_s: float) -> None:
        if len(msg.data) < MIN_FIELDS[sentence_type]:
            raise ValueError(f"{sentence_type.value} has {len(msg.data)} fields, needs {MIN_FIELDS[sentence_type]}")
        if sentence_type is SentenceType.VTG:
            if self._epoch_fix is None:
                return  # VTG carries no time: it follows an epoch that was already complete
            utc = self._epoch_utc
        else:
            utc = msg.timestamp
            if not isinstance(utc, datetime.time):
                raise ValueError(f"{sentence_type.value} has no valid UTC time")
        if utc == self._emitted_utc:
            self.late += 1
            return
        if utc != self._epoch_utc or self._epoch_fix is None:
            self._emit()
            self._epoch_utc = utc
            self._epoch_types = set()
            self._epoch_fix = gnss_pb2.GnssFix()
            self._epoch_fix.header.sample_time_s = time_s - self.receiver_latency_s
        fix = self._epoch_fix
        if sentence_type is SentenceType.GGA:
            if not self._gga(msg, fix):
                return
        elif sentence_type is SentenceType.GST:
            fix.std_east_m = float(msg.std_dev_longitude or 0.0)
            fix.std_north_m = float(msg.std_dev_latitude or 0.0)
            fix.std_up_m = float(msg.std_dev_altitude or 0.0)
        elif sentence_type is SentenceType.RMC:
            if msg.status == "A":
                fix.speed_mps = float(msg.spd_over_grnd or 0.0) * KNOTS_TO_MPS
                fix.course_deg = float(msg.true_course or 0.0)
        else:
            fix.speed_mps = float(msg.spd_over_grnd_kmph or 0.0) * KMPH_TO_MPS
            fix.course_deg = float(msg.true_track or 0.0)
        self.sentences[sentence_type] += 1
        self._epoch_types.add(sentence_type)
        if self.expected_sentences <= self._epoch_types and SentenceType.GGA in self._epoch_types:
            self._emit()

    def _gga(self, msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> bool:
        quality = int(msg.gps_qual or 0)
        if quality not in self._quality_map:
            self.bad[BadSentence.UNKNOWN_QUALITY] += 1
            return False
        fix.fix_mode = self._quality_map[quality]
        if fix.fix_mode != gnss_pb2.FIX_MODE_NO_FIX:
            fix.latitude_deg = msg.latitude
            fix.longitude_deg = msg.longitude
            # Ellipsoidal height = height above the geoid + geoid separation.
            fix.altitude_m = float(msg.altitude or 0.0) + float(msg.geo_sep or 0.0)
        fix.satellites = int(msg.num_sats or 0)
        fix.hdop = float(msg.horizontal_dil or 0.0)
        return True

    def _emit(self) -> None:
        fix = self._epoch_fix
        if fix is None or SentenceType.GGA not in self._epoch_types:
            return
        self._sequence += 1
        fix.header.sequence = self._sequence
        fix.header.vehicle_id = self._vehicle_id
        fix.header.sender = self._sender
        self._emitted_utc = self._epoch_utc
        self._epoch_fix = None
        self._epoch_types = set()
        self._on_fix(fix)
