"""An NMEA log file (as gpsd, a chart plotter or `cat /dev/ttyACM0 > log` wrote it) -> the chunks a GNSS port
would have delivered, each stamped with when it arrived: what geolocation publishes on gnss/nmea live.

A log holds no arrival times, so each line is stamped with the receiver's own clock: the UTC time of the latest
GGA, RMC, GNS or ZDA, on the date of the latest RMC or ZDA (lines before the first time take the first time, and
before the first date the first date). Stamps never go backwards (some receivers date RMC a second ahead of
GGA). Lines starting with '#' are comments (gpsd's headers); every other byte is kept, bad lines included, so
the decoder counts them as it would live.
"""

from __future__ import annotations

import datetime
from dataclasses import dataclass, field
from pathlib import Path

import pynmea2

from coopdrive.gnss.nmea_decoder import DAY_S, nmea_checksum

TIMED_TYPES = ("GGA", "RMC", "GNS", "ZDA")
EPOCH_DATE = datetime.date(1970, 1, 1)


@dataclass
class NmeaLog:
    # (arrival time, seconds since 1970 UTC; bytes as the port delivered them), in order.
    chunks: list[tuple[float, bytes]] = field(default_factory=list)
    comment_lines: int = 0
    timed_lines: int = 0  # lines whose UTC time stamped the ones after them
    dated: bool = False  # False: no RMC/ZDA date in the log, times are on 1970-01-01

    def append(self, time_s: float, line: bytes) -> None:
        """A line joins the last chunk when it has the same stamp."""
        if self.chunks and self.chunks[-1][0] == time_s:
            self.chunks[-1] = (time_s, self.chunks[-1][1] + line)
        else:
            self.chunks.append((time_s, line))


def _time_and_date(line: bytes) -> tuple[float | None, datetime.date | None]:
    """Seconds since midnight and date of a checksummed GGA/RMC/GNS/ZDA line, else (None, None)."""
    text = line.strip().decode("ascii", errors="replace")
    body, star, checksum = text[1:].rpartition("*")
    if not text.startswith("$") or not star or body[2:5] not in TIMED_TYPES:
        return None, None
    try:
        if int(checksum[:2], 16) != nmea_checksum(body):
            return None, None
        msg = pynmea2.parse(text, check=False)
    except (ValueError, pynmea2.ParseError):
        return None, None
    utc = getattr(msg, "timestamp", None)
    day_s = (utc.hour * 3600.0 + utc.minute * 60.0 + utc.second + utc.microsecond * 1e-6
             if isinstance(utc, datetime.time) else None)
    date = None
    if body[2:5] == "RMC" and isinstance(getattr(msg, "datestamp", None), datetime.date):
        date = msg.datestamp
    elif body[2:5] == "ZDA" and msg.day and msg.month and msg.year:
        try:
            date = datetime.date(int(msg.year), int(msg.month), int(msg.day))
        except ValueError:
            date = None
    return day_s, date


def _midnight_s(date: datetime.date) -> float:
    return datetime.datetime.combine(date, datetime.time(), tzinfo=datetime.timezone.utc).timestamp()


def read_nmea_log(path: str | Path, rate_hz: float | None = None, start_s: float = 0.0) -> NmeaLog:
    """The log's lines grouped into chunks of equal stamps (one chunk per receiver epoch, roughly).

    rate_hz: for a log whose times are missing or wrong, the receiver's stated rate instead: each GGA or GNS
    starts the next epoch, 1 / rate_hz after the one before, the first at start_s."""
    lines = Path(path).read_bytes().splitlines(keepends=True)
    if rate_hz is not None:
        return _at_rate(lines, rate_hz, start_s)
    log = NmeaLog()
    stamped: list[tuple[float | None, datetime.date | None, bytes]] = []
    for line in lines:
        if line.startswith(b"#"):
            log.comment_lines += 1
            continue
        day_s, date = _time_and_date(line)
        stamped.append((day_s, date, line))
    first_s = next((day_s for day_s, _, _ in stamped if day_s is not None), 0.0)
    date = next((date for _, date, _ in stamped if date is not None), None)
    log.dated = date is not None
    midnight_s = _midnight_s(date or EPOCH_DATE)
    now_s = midnight_s + first_s
    for day_s, line_date, line in stamped:
        if line_date is not None and line_date != date:
            date, midnight_s = line_date, _midnight_s(line_date)
        if day_s is not None:
            log.timed_lines += 1
            time_s = midnight_s + day_s
            if time_s < now_s - DAY_S / 2.0:
                time_s += DAY_S  # past midnight before the next date came
            now_s = max(now_s, time_s)
        log.append(now_s, line)
    return log


def _at_rate(lines: list[bytes], rate_hz: float, start_s: float) -> NmeaLog:
    if not rate_hz > 0.0:
        raise ValueError(f"rate_hz must be positive, got {rate_hz}")
    log, epochs = NmeaLog(), -1
    for line in lines:
        if line.startswith(b"#"):
            log.comment_lines += 1
            continue
        if line[3:6] in (b"GGA", b"GNS") and line.startswith(b"$"):
            epochs += 1
            log.timed_lines += 1
        time_s = start_s + max(epochs, 0) / rate_hz
        log.append(time_s, line)
    return log
