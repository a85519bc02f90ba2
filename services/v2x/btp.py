"""Basic Transport Protocol type B (EN 302 636-5-1): destination port + destination port info."""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass

from coopdrive.services.v2x.reasons import RejectReason, V2xDecodeError

_BTP_B = struct.Struct(">HH")
BTP_HEADER_SIZE = _BTP_B.size


class BtpPort(enum.IntEnum):
    """Well-known BTP-B destination ports; GCDC 2016 carried iCLCM on 2010."""

    CAM = 2001
    DENM = 2002
    ICLCM = 2010


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
