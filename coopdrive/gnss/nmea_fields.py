"""What each NMEA 0183 sentence the decoder uses puts into a GnssFix (pynmea2 parses, this reads the fields).

Every function takes a parsed sentence and the epoch's GnssFix, fills what the sentence measured, and raises
ValueError (or TypeError on a malformed number) when a field it needs is present but unusable.
"""

from __future__ import annotations

import datetime
import enum

import pynmea2

from coopdrive.v1 import gnss_pb2

KNOTS_TO_MPS = 1852.0 / 3600.0
KMPH_TO_MPS = 1.0 / 3.6

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

# GNS mode indicator, one letter per constellation (NMEA 4.x); the best letter gives the fix mode.
GNS_MODE_FIX_MODE = {
    "A": gnss_pb2.FIX_MODE_SINGLE,  # autonomous
    "P": gnss_pb2.FIX_MODE_SINGLE,  # precise (no differential corrections)
    "D": gnss_pb2.FIX_MODE_DGPS,
    "F": gnss_pb2.FIX_MODE_RTK_FLOAT,
    "R": gnss_pb2.FIX_MODE_RTK_FIXED,
}

# THS mode indicator: only A (autonomous) and D (differential) are measured headings.
THS_VALID_MODES = ("A", "D")


class SentenceType(enum.Enum):
    GGA = "GGA"
    RMC = "RMC"
    GST = "GST"
    VTG = "VTG"
    GNS = "GNS"  # position like GGA, with a mode letter per constellation
    HDT = "HDT"  # true heading (dual antenna), no time: belongs to the epoch it is sent with
    THS = "THS"  # true heading with a mode indicator (NMEA 4.x successor of HDT)
    ZDA = "ZDA"  # date and time only: dates the epochs


# Sentences that carry no UTC time of their own: they join the epoch being assembled.
TIMELESS = frozenset({SentenceType.VTG, SentenceType.HDT, SentenceType.THS})
POSITION_SENTENCES = frozenset({SentenceType.GGA, SentenceType.GNS})

# Fields a sentence must carry to be used (pynmea2 accepts short sentences and leaves fields missing).
MIN_FIELDS = {SentenceType.GGA: 10, SentenceType.RMC: 8, SentenceType.GST: 8, SentenceType.VTG: 8,
              SentenceType.GNS: 10, SentenceType.HDT: 1, SentenceType.THS: 2, SentenceType.ZDA: 4}


class Unusable(ValueError):
    """A sentence the receiver sent without the measurement (e.g. GGA quality 0 without a time)."""


def utc_time(msg: pynmea2.NMEASentence) -> datetime.time | None:
    value = getattr(msg, "timestamp", None)
    return value if isinstance(value, datetime.time) else None


def date_of(sentence_type: SentenceType, msg: pynmea2.NMEASentence) -> datetime.date | None:
    """The date an RMC or ZDA carries, None when it is empty."""
    if sentence_type is SentenceType.RMC:
        value = getattr(msg, "datestamp", None)
        return value if isinstance(value, datetime.date) else None
    if sentence_type is SentenceType.ZDA and msg.day and msg.month and msg.year:
        return datetime.date(int(msg.year), int(msg.month), int(msg.day))
    return None


def reports_no_fix(sentence_type: SentenceType, msg: pynmea2.NMEASentence) -> bool:
    """A receiver without a fix still sends its sentences, with empty fields and a no-fix flag."""
    data = msg.data
    if sentence_type is SentenceType.GGA:
        return len(data) > 5 and data[5] in ("", "0")
    if sentence_type is SentenceType.RMC:
        return len(data) > 1 and data[1] != "A"
    if sentence_type is SentenceType.GNS:
        return len(data) > 5 and not any(letter in GNS_MODE_FIX_MODE for letter in data[5])
    return False


def gga(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix, quality_map: dict[int, int]) -> None:
    quality = int(msg.gps_qual or 0)
    if quality not in quality_map:
        raise KeyError(quality)
    fix.fix_mode = quality_map[quality]
    _position(msg, fix, msg.horizontal_dil)


def _position(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix, hdop: str | None) -> None:
    """The position (when the fix mode has one), satellites and HDOP, which GGA and GNS carry alike."""
    if fix.fix_mode != gnss_pb2.FIX_MODE_NO_FIX:
        fix.latitude_deg = msg.latitude
        fix.longitude_deg = msg.longitude
        # Ellipsoidal height = height above the geoid + geoid separation.
        fix.altitude_m = float(msg.altitude or 0.0) + float(msg.geo_sep or 0.0)
    fix.satellites = int(msg.num_sats or 0)
    fix.hdop = float(hdop or 0.0)


def gns(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> None:
    """GNS fills the position only when the epoch's GGA did not (GGA is what most receivers are tuned for)."""
    if fix.fix_mode not in (gnss_pb2.FIX_MODE_UNSPECIFIED, gnss_pb2.FIX_MODE_NO_FIX):
        return
    modes = [GNS_MODE_FIX_MODE[letter] for letter in msg.mode_indicator or "" if letter in GNS_MODE_FIX_MODE]
    fix.fix_mode = max(modes, default=gnss_pb2.FIX_MODE_NO_FIX)
    _position(msg, fix, msg.hdop)


def gst(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> None:
    fix.std_east_m = float(msg.std_dev_longitude or 0.0)
    fix.std_north_m = float(msg.std_dev_latitude or 0.0)
    fix.std_up_m = float(msg.std_dev_altitude or 0.0)


def rmc(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> None:
    if msg.status == "A" and msg.spd_over_grnd not in (None, ""):
        fix.speed_mps = float(msg.spd_over_grnd) * KNOTS_TO_MPS
        fix.course_deg = float(msg.true_course or 0.0)
        fix.velocity_valid = True


def vtg(msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> None:
    # Mode indicator N (NMEA 2.3+): the receiver has no velocity, whatever the fields say.
    if len(msg.data) > 8 and msg.data[8] == "N":
        return
    if msg.spd_over_grnd_kmph not in (None, ""):
        speed_mps = float(msg.spd_over_grnd_kmph) * KMPH_TO_MPS
    elif msg.spd_over_grnd_kts not in (None, ""):
        speed_mps = float(msg.spd_over_grnd_kts) * KNOTS_TO_MPS
    else:
        return
    fix.speed_mps = speed_mps
    fix.course_deg = float(msg.true_track or 0.0)
    fix.velocity_valid = True


def heading(sentence_type: SentenceType, msg: pynmea2.NMEASentence, fix: gnss_pb2.GnssFix) -> None:
    """HDT (heading, T) or THS (heading, mode): empty fields mean the receiver has no heading this epoch."""
    value = msg.data[0]
    if value == "":
        return
    if sentence_type is SentenceType.THS and msg.data[1] not in THS_VALID_MODES:
        return
    fix.heading_deg = float(value) % 360.0
    fix.heading_valid = True
