"""An NMEA log (a receiver's byte stream saved to a file, gpsd-style `#` comments allowed) as gnss/nmea chunks.

One chunk per sentence, in file order, so the estimator reads the stream as the port delivered it. Every line
but a `#` comment goes into the recording, bad ones included (the estimator counts them as it would on the
vehicle); the import counts them per reason too.

Arrival times come from the receiver's UTC: a sentence with a time (GGA, RMC, ZDA) starts its epoch at that
time on the date of the latest RMC or ZDA (the first one for sentences before it); the sentences after it are
1 ms apart, which keeps the file's order and puts each fix on the wire when the receiver measured it. A log
without UTC times takes `--nmea-rate HZ`: one epoch per position sentence, starting at 0 s.
"""

from __future__ import annotations

import datetime as dt
import re
from dataclasses import dataclass
from pathlib import Path

import pynmea2

from coopdrive.recording.import_source import ImportFailure, SourceReport, TimedMessage
from coopdrive.v1 import gnss_pb2

TOPIC = "gnss/nmea"
SENTENCE_SPACING_S = 0.001
TIMED_SENTENCES = ("GGA", "RMC", "ZDA")
POSITION_SENTENCES = ("GGA", "RMC", "GLL", "GNS")
# A day rolls over when the time of day falls back by more than this without a new date.
ROLLOVER_S = 12 * 3600.0
_SENTENCE_START = re.compile(rb"[$!]")
_CHECKSUM_END = re.compile(rb"\*[0-9A-Fa-f]{2}$")
_UNIX_EPOCH = dt.date(1970, 1, 1)


@dataclass
class _Line:
    data: bytes
    bad: str | None = None
    sentence_type: str | None = None
    seconds_of_day: float | None = None
    date: dt.date | None = None


def read_nmea_log(path: Path, rate_hz: float | None = None) -> SourceReport:
    report = SourceReport("nmea", path)
    lines = [line for raw in _raw_lines(path.read_bytes()) for line in _split_sentences(raw)]
    for line in lines:
        report.items_read += 1
        _classify(line)
        if line.bad:
            report.bad[line.bad] += 1
        elif line.sentence_type is None:
            report.notes["unknown_sentence_type"] += 1
    times = _rate_times(lines, rate_hz) if rate_hz else _utc_times(lines, report, path)
    for line, time_s in zip(lines, times):
        report.messages.append(TimedMessage(time_s, TOPIC, gnss_pb2.NmeaChunk(data=line.data, port=path.name)))
    return report


def _raw_lines(data: bytes) -> list[bytes]:
    """Lines with their endings; `#` comments and blank lines left out."""
    return [line for line in data.splitlines(keepends=True) if line.strip() and not line.startswith(b"#")]


def _split_sentences(raw: bytes) -> list[_Line]:
    """A line holding a cut sentence and then a whole one (a receiver restarting mid-line) gives both."""
    starts = [m.start() for m in _SENTENCE_START.finditer(raw)]
    if len(starts) <= 1:
        return [_Line(raw)]
    cuts = ([0] if starts[0] > 0 else []) + starts + [len(raw)]
    return [_Line(raw[a:b]) for a, b in zip(cuts, cuts[1:]) if raw[a:b].strip()]


def _classify(line: _Line) -> None:
    try:
        text = line.data.decode("ascii").strip()
    except UnicodeDecodeError:
        line.bad = "binary_junk"
        return
    if not text.isprintable():
        line.bad = "binary_junk"
    elif text[0] not in "$!":
        line.bad = "not_nmea"
    elif not _CHECKSUM_END.search(text.encode()):
        line.bad = "truncated"  # the checksum ends a sentence: a cut one has none
    else:
        _parse(line, text)


def _parse(line: _Line, text: str) -> None:
    try:
        sentence = pynmea2.parse(text, check=True)
    except pynmea2.ChecksumError:
        line.bad = "bad_checksum"
        return
    except pynmea2.SentenceTypeError:
        return  # well formed, of a type pynmea2 does not know: kept, noted
    except (pynmea2.ParseError, ValueError):
        line.bad = "unparsable"
        return
    line.sentence_type = getattr(sentence, "sentence_type", None) or type(sentence).__name__
    if line.sentence_type not in TIMED_SENTENCES:
        return
    stamp = getattr(sentence, "timestamp", None)
    if isinstance(stamp, dt.time):
        line.seconds_of_day = stamp.hour * 3600 + stamp.minute * 60 + stamp.second + stamp.microsecond / 1e6
    try:
        line.date = sentence.datestamp if line.sentence_type in ("RMC", "ZDA") else None
    except (TypeError, ValueError):
        line.date = None  # empty date fields


def _utc_times(lines: list[_Line], report: SourceReport, path: Path) -> list[float]:
    first_date = next((line.date for line in lines if line.date is not None), None)
    if not any(line.seconds_of_day is not None for line in lines):
        raise ImportFailure(f"{path}: no UTC time in any GGA, RMC or ZDA sentence; give --nmea-rate HZ")
    if first_date is None:
        report.notes["no_date_times_are_seconds_of_1970_01_01"] += 1
    day = first_date or _UNIX_EPOCH
    # Sentences before the first time are stamped as the first epoch's.
    first_s = next(_unix_s(day, line.seconds_of_day) for line in lines if line.seconds_of_day is not None)
    epoch_s = None
    times, index_in_epoch, last_s = [], 0, float("-inf")
    for line in lines:
        if line.date is not None:
            day = line.date
        if line.seconds_of_day is not None:
            start_s = _unix_s(day, line.seconds_of_day)
            if epoch_s is not None and start_s < epoch_s - ROLLOVER_S and line.date is None:
                day += dt.timedelta(days=1)
                start_s = _unix_s(day, line.seconds_of_day)
            if epoch_s is not None and start_s < epoch_s:
                report.notes["utc_time_went_back"] += 1
            if start_s != epoch_s:
                epoch_s, index_in_epoch = start_s, 0
        # Strictly increasing, so the recording's log-time order is the file's order.
        last_s = max((first_s if epoch_s is None else epoch_s) + index_in_epoch * SENTENCE_SPACING_S, last_s + 1e-6)
        times.append(last_s)
        index_in_epoch += 1
    return times


def _rate_times(lines: list[_Line], rate_hz: float) -> list[float]:
    """No UTC in the log: the first position sentence type seen starts each epoch, 1/rate apart."""
    marker = next((line.sentence_type for line in lines if line.sentence_type in POSITION_SENTENCES), None)
    epoch, index_in_epoch, times, marker_seen = 0, 0, [], False
    for line in lines:
        if line.sentence_type == marker is not None:
            if marker_seen:
                epoch, index_in_epoch = epoch + 1, 0
            marker_seen = True
        times.append(epoch / rate_hz + index_in_epoch * SENTENCE_SPACING_S)
        index_in_epoch += 1
    return times


def _unix_s(day: dt.date, seconds_of_day: float) -> float:
    midnight = dt.datetime(day.year, day.month, day.day, tzinfo=dt.timezone.utc)
    return midnight.timestamp() + seconds_of_day
