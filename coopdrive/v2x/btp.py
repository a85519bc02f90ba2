"""Basic Transport Protocol type B (EN 302 636-5-1): destination port + destination port info."""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass

from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

_BTP_B = struct.Struct(">HH")
BTP_HEADER_SIZE = _BTP_B.size


class BtpPort(enum.IntEnum):
    """Well-known BTP-B destination ports (ETSI TS 103 248); GCDC 2016 carried iCLCM on 2010."""

    CAM = 2001
    DENM = 2002
    MAPEM = 2003
    SPATEM = 2004
    IVIM = 2006
    SREM = 2007
    SSEM = 2008
    CPM = 2009
    ICLCM = 2010
    VAM = 2018


# What each port of TS 103 248 carries, by our message-type names (2010 is EVCSN POI there, iCLCM at GCDC).
MESSAGE_NAME_OF_PORT = {
    2001: "cam", 2002: "denm", 2003: "mapem", 2004: "spatem", 2005: "saem", 2006: "ivim", 2007: "srem",
    2008: "ssem", 2009: "cpm", 2010: "iclcm", 2011: "tpg", 2012: "ev_rsr", 2013: "rtcmem", 2014: "ctlm",
    2015: "crlm", 2016: "ec_at_request", 2017: "mcdm", 2018: "vam", 2019: "imzm"}


class BtpParseError(V2xDecodeError):
    """A BTP header that could not be parsed."""


@dataclass(slots=True)
class BtpBHeader:
    destination_port: int
    destination_port_info: int = 0

    def pack(self) -> bytes:
        return _BTP_B.pack(self.destination_port, self.destination_port_info)


def parse_btp_b(data: bytes) -> tuple[BtpBHeader, bytes]:
    """Split a BTP-B packet into its header and payload."""
    if len(data) < BTP_HEADER_SIZE:
        raise BtpParseError(RejectReason.TRUNCATED_BTP_HEADER, f"{len(data)} bytes")
    port, info = _BTP_B.unpack_from(data)
    return BtpBHeader(port, info), bytes(data[BTP_HEADER_SIZE:])
