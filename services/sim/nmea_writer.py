"""NMEA 0183 sentences (GGA, RMC, GST, VTG) as bytes with their checksums, from physical values."""
from __future__ import annotations

import datetime as dt
import enum
from dataclasses import dataclass, replace

import pynmea2

from coopdrive.v1 import gnss_pb2

KNOTS_PER_MPS = 3600.0 / 1852.0
KMH_PER_MPS = 3.6


class GgaQuality(enum.IntEnum):
    INVALID = 0
    GPS = 1
    DGPS = 2
    RTK_FIXED = 4
    RTK_FLOAT = 5
    # NovAtel (Heudiasyc's SPAN-CPT) reports a WAAS/EGNOS solution as 9; u-blox and NMEA 4.x use 2.
    SBAS_NOVATEL = 9


# NMEA 2.3+ mode indicator of RMC and VTG.
class ModeIndicator(enum.Enum):
    AUTONOMOUS = "A"
    DIFFERENTIAL = "D"
    RTK_FLOAT = "F"
    RTK_INTEGER = "R"
    NOT_VALID = "N"


_QUALITY = {
    gnss_pb2.FIX_MODE_NO_FIX: GgaQuality.INVALID,
    gnss_pb2.FIX_MODE_SINGLE: GgaQuality.GPS,
    gnss_pb2.FIX_MODE_SBAS: GgaQuality.DGPS,
    gnss_pb2.FIX_MODE_DGPS: GgaQuality.DGPS,
    gnss_pb2.FIX_MODE_RTK_FLOAT: GgaQuality.RTK_FLOAT,
    gnss_pb2.FIX_MODE_RTK_FIXED: GgaQuality.RTK_FIXED,
}
_MODE = {
    gnss_pb2.FIX_MODE_NO_FIX: ModeIndicator.NOT_VALID,
    gnss_pb2.FIX_MODE_SINGLE: ModeIndicator.AUTONOMOUS,
    gnss_pb2.FIX_MODE_SBAS: ModeIndicator.DIFFERENTIAL,
    gnss_pb2.FIX_MODE_DGPS: ModeIndicator.DIFFERENTIAL,
    gnss_pb2.FIX_MODE_RTK_FLOAT: ModeIndicator.RTK_FLOAT,
    gnss_pb2.FIX_MODE_RTK_FIXED: ModeIndicator.RTK_INTEGER,
}


def gga_quality(fix_mode: int) -> GgaQuality:
    return _QUALITY.get(fix_mode, GgaQuality.INVALID)


def checksum(body: str) -> str:
    """XOR of the characters between '$' and '*' (pynmea2's), as two upper-case hex digits."""
    return f"{pynmea2.NMEASentence.checksum(body):02X}"


def sentence(body: str) -> bytes:
    return f"${body}*{checksum(body)}\r\n".encode("ascii")


# Minutes are written with this many decimals (1e-7 min is about 0.2 mm).
_MINUTE_DECIMALS = 7


def _degrees_minutes(value_deg: float) -> tuple[int, float]:
    """Whole degrees and minutes, rounded first so that minutes never print as 60."""
    total_minutes = round(abs(value_deg) * 60.0, _MINUTE_DECIMALS)
    degrees = int(total_minutes // 60.0)
    return degrees, total_minutes - degrees * 60.0


def _latitude(lat_deg: float) -> tuple[str, str]:
    degrees, minutes = _degrees_minutes(lat_deg)
    return f"{degrees:02d}{minutes:0{_MINUTE_DECIMALS + 3}.{_MINUTE_DECIMALS}f}", "N" if lat_deg >= 0 else "S"


def _longitude(lon_deg: float) -> tuple[str, str]:
    degrees, minutes = _degrees_minutes(lon_deg)
    return f"{degrees:03d}{minutes:0{_MINUTE_DECIMALS + 3}.{_MINUTE_DECIMALS}f}", "E" if lon_deg >= 0 else "W"


def _position(fix: "NmeaFix", valid: bool) -> tuple[str, str, str, str]:
    """Receivers leave the position fields empty when they have no fix."""
    if not valid:
        return "", "", "", ""
    return (*_latitude(fix.latitude_deg), *_longitude(fix.longitude_deg))


def _round_to_centiseconds(utc: dt.datetime) -> dt.datetime:
    utc = utc + dt.timedelta(microseconds=5_000)
    return utc.replace(microsecond=utc.microsecond // 10_000 * 10_000)


def _time(utc: dt.datetime) -> str:
    return f"{utc:%H%M%S}.{utc.microsecond // 10_000:02d}"


@dataclass(frozen=True)
class NmeaFix:
    """One receiver solution in physical units."""

    utc: dt.datetime
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    fix_mode: int
    speed_mps: float
    course_deg: float
    std_north_m: float
    std_east_m: float
    std_up_m: float
    satellites: int
    hdop: float
    geoid_separation_m: float = 0.0
    differential_age_s: float | None = None


def _centisecond_fix(fix: NmeaFix) -> NmeaFix:
    """NMEA times have centiseconds: round (not truncate) so 0.2999999 s is labelled .30."""
    return replace(fix, utc=_round_to_centiseconds(fix.utc))


class NmeaWriter:
    """Writes GGA, RMC, GST and VTG sentences with a fixed talker id ("GN" multi-constellation, "GP" GPS)."""

    def __init__(self, talker_id: str = "GN", sbas_quality: GgaQuality = GgaQuality.SBAS_NOVATEL) -> None:
        if len(talker_id) != 2 or not talker_id.isalpha():
            raise ValueError(f"NMEA talker id must be two letters, got {talker_id!r}")
        if sbas_quality not in (GgaQuality.DGPS, GgaQuality.SBAS_NOVATEL):
            raise ValueError(f"an SBAS fix is reported as GGA quality 2 or 9, not {sbas_quality}")
        self.talker_id = talker_id.upper()
        self.sbas_quality = sbas_quality

    def quality(self, fix_mode: int) -> GgaQuality:
        if fix_mode == gnss_pb2.FIX_MODE_SBAS:
            return self.sbas_quality
        return gga_quality(fix_mode)

    def gga(self, fix: NmeaFix) -> bytes:
        fix = _centisecond_fix(fix)
        quality = self.quality(fix.fix_mode)
        lat, ns, lon, ew = _position(fix, quality is not GgaQuality.INVALID)
        age = f"{fix.differential_age_s:.1f}" if fix.differential_age_s is not None else ""
        station = "0000" if fix.differential_age_s is not None else ""
        return sentence(f"{self.talker_id}GGA,{_time(fix.utc)},{lat},{ns},{lon},{ew},{int(quality)},"
                        f"{fix.satellites:02d},{fix.hdop:.1f},{fix.altitude_m:.3f},M,"
                        f"{fix.geoid_separation_m:.3f},M,{age},{station}")

    def rmc(self, fix: NmeaFix) -> bytes:
        fix = _centisecond_fix(fix)
        mode = _MODE.get(fix.fix_mode, ModeIndicator.NOT_VALID)
        lat, ns, lon, ew = _position(fix, mode is not ModeIndicator.NOT_VALID)
        status = "V" if mode is ModeIndicator.NOT_VALID else "A"
        return sentence(f"{self.talker_id}RMC,{_time(fix.utc)},{status},{lat},{ns},{lon},{ew},"
                        f"{fix.speed_mps * KNOTS_PER_MPS:.3f},{fix.course_deg % 360.0:.2f},"
                        f"{fix.utc:%d%m%y},,,{mode.value}")

    def gst(self, fix: NmeaFix) -> bytes:
        fix = _centisecond_fix(fix)
        major = max(fix.std_north_m, fix.std_east_m)
        minor = min(fix.std_north_m, fix.std_east_m)
        orientation_deg = 0.0 if fix.std_north_m >= fix.std_east_m else 90.0
        rms = (fix.std_north_m ** 2 + fix.std_east_m ** 2 + fix.std_up_m ** 2) ** 0.5
        return sentence(f"{self.talker_id}GST,{_time(fix.utc)},{rms:.3f},{major:.3f},{minor:.3f},"
                        f"{orientation_deg:.1f},{fix.std_north_m:.3f},{fix.std_east_m:.3f},{fix.std_up_m:.3f}")

    def vtg(self, fix: NmeaFix) -> bytes:
        mode = _MODE.get(fix.fix_mode, ModeIndicator.NOT_VALID)
        return sentence(f"{self.talker_id}VTG,{fix.course_deg % 360.0:.2f},T,,M,"
                        f"{fix.speed_mps * KNOTS_PER_MPS:.3f},N,{fix.speed_mps * KMH_PER_MPS:.3f},K,{mode.value}")

    def epoch(self, fix: NmeaFix) -> list[bytes]:
        """The sentences a receiver sends for one solution, in the usual order."""
        return [self.gga(fix), self.rmc(fix), self.gst(fix), self.vtg(fix)]
