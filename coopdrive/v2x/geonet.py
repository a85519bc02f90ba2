"""GeoNetworking (EN 302 636-4-1) basic + common headers, SHB and GBC extended headers.

Only what GCDC-style V2X needs: single-hop broadcast (CAM, iCLCM) and geo-broadcast (DENM) with long
position vectors, and the beacons every real stack sends. Field values stay in wire units here (1e-7 deg, 0.01 m/s, 0.1 deg); packet.py converts.
Parsing never raises anything but GnParseError, whose reason names the first thing that was wrong.
"""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass, field

from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

GN_VERSION_GCDC = 0
GN_VERSION_CURRENT = 1
SUPPORTED_GN_VERSIONS = (GN_VERSION_GCDC, GN_VERSION_CURRENT)
# A GN address's MID is the station's link-layer (MAC) address.
MAC_SIZE_BYTES = 6

_BASIC = struct.Struct(">BBBB")
_COMMON = struct.Struct(">BBBBHBB")
_LONG_POSITION_VECTOR = struct.Struct(">QIiiHH")
_SHB_TAIL = struct.Struct(">I")
_SHB = struct.Struct(_LONG_POSITION_VECTOR.format + _SHB_TAIL.format[1:])  # both in one unpack
_ADDRESS_FLAGS_SIZE = 2  # M, ST and reserved bits ahead of the 6-octet MID
_GBC_HEAD = struct.Struct(">HH")
_GBC_AREA = struct.Struct(">iiHHHH")
BASIC_HEADER_SIZE = _BASIC.size
# The basic header's first octet: the GN version in the high nibble, the next header in the low one.
_BASIC_VERSION_BITS, _BASIC_NEXT_HEADER_BITS = 0xF0, 0x0F
COMMON_HEADER_SIZE = _COMMON.size
SHB_HEADER_SIZE = _LONG_POSITION_VECTOR.size + _SHB_TAIL.size
GBC_HEADER_SIZE = _GBC_HEAD.size + _LONG_POSITION_VECTOR.size + _GBC_AREA.size

_MOBILE_FLAG = 0x80
_PAI_FLAG = 0x8000
_SPEED_BITS = 15
_LIFETIME_BASES_S = (0.05, 1.0, 10.0, 100.0)
_LIFETIME_MAX_MULTIPLIER = 63


class GnParseError(V2xDecodeError):
    """A GeoNetworking header that could not be parsed."""


class BasicNextHeader(enum.IntEnum):
    ANY = 0
    COMMON_HEADER = 1
    SECURED_PACKET = 2


class CommonNextHeader(enum.IntEnum):
    ANY = 0
    BTP_A = 1
    BTP_B = 2
    IPV6 = 3


class HeaderType(enum.IntEnum):
    ANY = 0
    BEACON = 1
    GEOUNICAST = 2
    GEOANYCAST = 3
    GEOBROADCAST = 4
    TOPOLOGICALLY_SCOPED_BROADCAST = 5
    LOCATION_SERVICE = 6


class GeoAreaShape(enum.IntEnum):
    """Header subtype of GEOBROADCAST / GEOANYCAST."""

    CIRCLE = 0
    RECTANGLE = 1
    ELLIPSE = 2


TSB_SUBTYPE_SINGLE_HOP = 0

# Lookups by wire number: calling an IntEnum class costs as much as parsing a whole header.
_BASIC_NEXT_BY_NUMBER = {int(member): member for member in
                         (BasicNextHeader.COMMON_HEADER, BasicNextHeader.SECURED_PACKET)}
_COMMON_NEXT_BY_NUMBER = {int(member): member for member in CommonNextHeader}
_SHAPE_BY_SUBTYPE = {int(member): member for member in GeoAreaShape}


def encode_lifetime(lifetime_s: float) -> tuple[int, int]:
    """(multiplier, base index) of the finest base that can hold lifetime_s."""
    for base_index, base_s in enumerate(_LIFETIME_BASES_S):
        multiplier = round(lifetime_s / base_s)
        if multiplier <= _LIFETIME_MAX_MULTIPLIER:
            return max(multiplier, 0), base_index
    return _LIFETIME_MAX_MULTIPLIER, len(_LIFETIME_BASES_S) - 1


@dataclass(slots=True)
class BasicHeader:
    version: int = GN_VERSION_CURRENT
    next_header: BasicNextHeader = BasicNextHeader.COMMON_HEADER
    lifetime_multiplier: int = 1
    lifetime_base: int = 1
    remaining_hop_limit: int = 1

    @property
    def lifetime_s(self) -> float:
        return self.lifetime_multiplier * _LIFETIME_BASES_S[self.lifetime_base]


@dataclass(slots=True)
class CommonHeader:
    next_header: CommonNextHeader = CommonNextHeader.BTP_B
    header_type: HeaderType = HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST
    header_subtype: int = TSB_SUBTYPE_SINGLE_HOP
    # Traffic class octet: store-carry-forward (bit 7), channel offload (bit 6), TC ID (bits 5-0).
    traffic_class: int = 0
    mobile: bool = True
    payload_length: int = 0
    max_hop_limit: int = 1


@dataclass(slots=True)
class GnAddress:
    manual: bool = False
    station_type: int = 5
    reserved: int = 0
    mid: bytes = bytes(MAC_SIZE_BYTES)


@dataclass(slots=True)
class LongPositionVector:
    address: GnAddress = field(default_factory=GnAddress)
    # TAI milliseconds mod 2^32.
    timestamp_ms: int = 0
    latitude_tenth_microdeg: int = 0
    longitude_tenth_microdeg: int = 0
    position_accurate: bool = False
    speed_cmps: int = 0
    # 0.1 deg from north, clockwise.
    heading_tenth_deg: int = 0

    def pack(self) -> bytes:
        a = self.address
        address = (int(a.manual) << 63) | ((a.station_type & 0x1F) << 58) | ((a.reserved & 0x3FF) << 48) | \
            int.from_bytes(a.mid, "big")
        speed = (_PAI_FLAG if self.position_accurate else 0) | (self.speed_cmps & 0x7FFF)
        return _LONG_POSITION_VECTOR.pack(address, self.timestamp_ms & 0xFFFFFFFF, self.latitude_tenth_microdeg,
                                          self.longitude_tenth_microdeg, speed, self.heading_tenth_deg)

    @classmethod
    def unpack_from(cls, data: bytes, offset: int) -> LongPositionVector:
        return cls.from_fields(data, offset, *_LONG_POSITION_VECTOR.unpack_from(data, offset))

    @classmethod
    def from_fields(cls, data: bytes, offset: int, address: int, timestamp: int, latitude: int, longitude: int,
                    speed: int, heading: int) -> LongPositionVector:
        """From the unpacked fields of the vector at data[offset:]; the MID is sliced rather than re-encoded."""
        speed_cmps = speed & 0x7FFF
        if speed_cmps >= 1 << (_SPEED_BITS - 1):
            speed_cmps -= 1 << _SPEED_BITS
        mid = bytes(data[offset + _ADDRESS_FLAGS_SIZE:offset + _ADDRESS_FLAGS_SIZE + MAC_SIZE_BYTES])
        return cls(GnAddress(address >= 1 << 63, (address >> 58) & 0x1F, (address >> 48) & 0x3FF, mid),
                   timestamp, latitude, longitude, bool(speed & _PAI_FLAG), speed_cmps, heading)


@dataclass(slots=True)
class ShbHeader:
    source_position: LongPositionVector = field(default_factory=LongPositionVector)
    # DCC / media-dependent octets (reserved in GN version 0).
    media_dependent: int = 0


@dataclass(slots=True)
class BeaconHeader:
    """A GN beacon: the sender's position vector only, no payload (EN 302 636-4-1, 9.8.6)."""

    source_position: LongPositionVector = field(default_factory=LongPositionVector)


BEACON_HEADER_SIZE = _LONG_POSITION_VECTOR.size


@dataclass(slots=True)
class GeoArea:
    shape: GeoAreaShape = GeoAreaShape.CIRCLE
    latitude_tenth_microdeg: int = 0
    longitude_tenth_microdeg: int = 0
    distance_a_m: int = 0
    distance_b_m: int = 0
    # Azimuth of the long side, degrees from north, clockwise.
    angle_deg: int = 0


@dataclass(slots=True)
class GbcHeader:
    sequence_number: int = 0
    source_position: LongPositionVector = field(default_factory=LongPositionVector)
    area: GeoArea = field(default_factory=GeoArea)


@dataclass(slots=True)
class GnPacket:
    basic: BasicHeader
    common: CommonHeader
    extended: ShbHeader | GbcHeader | BeaconHeader
    payload: bytes

    def to_bytes(self) -> bytes:
        """Serialise; payload length, header type and subtype are set from the payload and extended header."""
        b, c = self.basic, self.common
        c.payload_length = len(self.payload)
        if isinstance(self.extended, GbcHeader):
            c.header_type, c.header_subtype = HeaderType.GEOBROADCAST, int(self.extended.area.shape)
        elif isinstance(self.extended, BeaconHeader):
            c.header_type, c.header_subtype = HeaderType.BEACON, 0
        else:
            c.header_type, c.header_subtype = HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST, TSB_SUBTYPE_SINGLE_HOP
        parts = [
            _BASIC.pack((b.version << 4) | int(b.next_header), 0, (b.lifetime_multiplier << 2) | b.lifetime_base,
                        b.remaining_hop_limit),
            _COMMON.pack(int(c.next_header) << 4, (int(c.header_type) << 4) | c.header_subtype, c.traffic_class,
                         _MOBILE_FLAG if c.mobile else 0, c.payload_length, c.max_hop_limit, 0),
        ]
        if isinstance(self.extended, GbcHeader):
            area = self.extended.area
            parts += [_GBC_HEAD.pack(self.extended.sequence_number, 0), self.extended.source_position.pack(),
                      _GBC_AREA.pack(area.latitude_tenth_microdeg, area.longitude_tenth_microdeg, area.distance_a_m,
                                     area.distance_b_m, area.angle_deg, 0)]
        elif isinstance(self.extended, BeaconHeader):
            parts.append(self.extended.source_position.pack())
        else:
            parts += [self.extended.source_position.pack(), _SHB_TAIL.pack(self.extended.media_dependent)]
        parts.append(self.payload)
        return b"".join(parts)


def parse_basic_header(data: bytes, accepted_versions: tuple[int, ...] = SUPPORTED_GN_VERSIONS) -> BasicHeader:
    """The basic header of a packet whose next header is the common header or a secured packet."""
    if len(data) < BASIC_HEADER_SIZE:
        raise GnParseError(RejectReason.TRUNCATED_BASIC_HEADER, f"{len(data)} bytes")
    version_next, _, lifetime, hop_limit = _BASIC.unpack_from(data, 0)
    version, basic_next = version_next >> 4, version_next & _BASIC_NEXT_HEADER_BITS
    if version not in accepted_versions:
        raise GnParseError(RejectReason.UNSUPPORTED_GN_VERSION, f"version {version}")
    next_header = _BASIC_NEXT_BY_NUMBER.get(basic_next)
    if next_header is None:
        raise GnParseError(RejectReason.UNKNOWN_BASIC_NEXT_HEADER, f"next header {basic_next}")
    return BasicHeader(version, next_header, lifetime >> 2, lifetime & 0x03, hop_limit)


def is_secured(packet: bytes) -> bool:
    """Whether the basic header says a security envelope follows, read from its first octet alone."""
    return len(packet) >= BASIC_HEADER_SIZE and packet[0] & _BASIC_NEXT_HEADER_BITS == BasicNextHeader.SECURED_PACKET


def with_basic_next_header(packet: bytes, next_header: BasicNextHeader, rest: bytes) -> bytes:
    """packet's basic header with next_header, followed by rest (to wrap or unwrap a security envelope)."""
    first = (packet[0] & _BASIC_VERSION_BITS) | int(next_header)
    return bytes([first]) + bytes(packet[1:BASIC_HEADER_SIZE]) + rest


def parse_gn(data: bytes, accepted_versions: tuple[int, ...] = SUPPORTED_GN_VERSIONS) -> GnPacket:
    """Parse an SHB, GBC or beacon packet. Bytes after the payload length (Ethernet padding) are dropped."""
    basic = parse_basic_header(data, accepted_versions)
    if basic.next_header == BasicNextHeader.SECURED_PACKET:
        raise GnParseError(RejectReason.SECURED_PACKET_UNSUPPORTED)
    if len(data) < BASIC_HEADER_SIZE + COMMON_HEADER_SIZE:
        raise GnParseError(RejectReason.TRUNCATED_COMMON_HEADER, f"{len(data)} bytes")
    next_reserved, type_subtype, traffic_class, flags, payload_length, max_hop, _ = _COMMON.unpack_from(
        data, BASIC_HEADER_SIZE)
    header_type, subtype = type_subtype >> 4, type_subtype & 0x0F
    offset = BASIC_HEADER_SIZE + COMMON_HEADER_SIZE
    if header_type == HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST and subtype == TSB_SUBTYPE_SINGLE_HOP:
        extended_size, header_type = SHB_HEADER_SIZE, HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST
    elif header_type == HeaderType.GEOBROADCAST and subtype in _SHAPE_BY_SUBTYPE:
        extended_size, header_type = GBC_HEADER_SIZE, HeaderType.GEOBROADCAST
    elif header_type == HeaderType.BEACON:
        extended_size, header_type = BEACON_HEADER_SIZE, HeaderType.BEACON
    else:
        raise GnParseError(RejectReason.UNSUPPORTED_HEADER_TYPE, f"type {header_type} subtype {subtype}")
    common_next = _COMMON_NEXT_BY_NUMBER.get(next_reserved >> 4, CommonNextHeader.ANY)
    common = CommonHeader(common_next, header_type, subtype, traffic_class,
                          bool(flags & _MOBILE_FLAG), payload_length, max_hop)
    if len(data) < offset + extended_size:
        raise GnParseError(RejectReason.TRUNCATED_EXTENDED_HEADER, f"{len(data)} bytes")
    if header_type == HeaderType.GEOBROADCAST:
        sequence_number, _ = _GBC_HEAD.unpack_from(data, offset)
        position = LongPositionVector.unpack_from(data, offset + _GBC_HEAD.size)
        latitude, longitude, a_m, b_m, angle_deg, _ = _GBC_AREA.unpack_from(
            data, offset + _GBC_HEAD.size + _LONG_POSITION_VECTOR.size)
        extended = GbcHeader(sequence_number, position,
                             GeoArea(_SHAPE_BY_SUBTYPE[subtype], latitude, longitude, a_m, b_m, angle_deg))
    elif header_type == HeaderType.BEACON:
        extended = BeaconHeader(LongPositionVector.unpack_from(data, offset))
    else:
        address, timestamp, latitude, longitude, speed, heading, media_dependent = _SHB.unpack_from(data, offset)
        extended = ShbHeader(LongPositionVector.from_fields(
            data, offset, address, timestamp, latitude, longitude, speed, heading), media_dependent)
    offset += extended_size
    if len(data) - offset < payload_length:
        raise GnParseError(RejectReason.PAYLOAD_LENGTH_MISMATCH,
                           f"header says {payload_length} bytes, {len(data) - offset} present")
    return GnPacket(basic, common, extended, bytes(data[offset:offset + payload_length]))
