"""Pieces shared by the CAM and DENM mappings: positions, path points, bit flags, enumerations."""

from __future__ import annotations

from collections.abc import Sequence

from google.protobuf.message import Message

from coopdrive.v2x import units
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_GCDC
from coopdrive.v2x.reasons import V2xEncodeError
from coopdrive.v1 import its_pb2


def wire_protocol_version(content_version: int) -> int:
    """A content message's protocol_version left at 0 (unset) means the GCDC default."""
    return content_version or PROTOCOL_VERSION_GCDC


def checked_code(wire_name: str, value: int, low: int, high: int) -> int:
    """An identifier or code that no clamp could make right: outside low..high it is refused."""
    if not low <= value <= high:
        raise V2xEncodeError(f"{wire_name} {value} is outside {low}..{high}")
    return value


class EnumTable:
    """ASN.1 ENUMERATED names <-> protobuf enum numbers."""

    def __init__(self, pairs: Sequence[tuple[str, int]], unknown_extension: int | None = None):
        """unknown_extension: what an extensible ENUMERATED's value added after our schema maps to
        (asn1tools decodes it as None); without it such a value is refused."""
        self._to_proto = dict(pairs)
        self._to_asn = {number: name for name, number in pairs}
        self._unknown_extension = unknown_extension

    def to_asn(self, number: int) -> str:
        try:
            return self._to_asn[number]
        except KeyError:
            raise V2xEncodeError(f"no wire value for enum number {number}") from None

    def to_proto(self, name: str | None) -> int:
        if name is None and self._unknown_extension is not None:
            return self._unknown_extension
        try:
            return self._to_proto[name]
        except KeyError:
            raise ValueError(f"unknown enumerated value {name!r}") from None


def flags_to_bits(flags: Message, names: Sequence[str]) -> tuple[bytes, int]:
    """A message of bools -> asn1tools BIT STRING (bytes, nbits), field i at bit i (MSB first)."""
    value = 0
    for name in names:
        value = (value << 1) | int(getattr(flags, name))
    nbits = len(names)
    padding = -nbits % 8
    return (value << padding).to_bytes((nbits + padding) // 8, "big"), nbits


def bits_to_flags(bits: tuple[bytes, int], flags: Message, names: Sequence[str]) -> None:
    data, nbits = bits
    value = int.from_bytes(data, "big") >> (len(data) * 8 - nbits) if data else 0
    for index, name in enumerate(names):
        if index < nbits:
            setattr(flags, name, bool((value >> (nbits - 1 - index)) & 1))


def bools_to_bits(values: Sequence[bool]) -> tuple[bytes, int]:
    value = 0
    for flag in values:
        value = (value << 1) | int(flag)
    padding = -len(values) % 8
    return (value << padding).to_bytes((len(values) + padding) // 8, "big"), len(values)


def bits_to_bools(bits: tuple[bytes, int]) -> list[bool]:
    data, nbits = bits
    value = int.from_bytes(data, "big") >> (len(data) * 8 - nbits) if data else 0
    return [bool((value >> (nbits - 1 - index)) & 1) for index in range(nbits)]


def optional(message: Message, field: str) -> float | None:
    return getattr(message, field) if message.HasField(field) else None


def set_optional(message: Message, field: str, value: float | None) -> None:
    """Set field unless value is None ('unavailable'); messages being decoded start with every field absent."""
    if value is not None:
        setattr(message, field, value)


def reference_position_to_asn(position: its_pb2.ReferencePosition) -> dict:
    return {
        "latitude": units.LATITUDE_TENTH_MICRODEG.to_wire(optional(position, "latitude_deg")),
        "longitude": units.LONGITUDE_TENTH_MICRODEG.to_wire(optional(position, "longitude_deg")),
        "positionConfidenceEllipse": {
            "semiMajorConfidence": units.SEMI_AXIS_LENGTH_CM.to_wire(optional(position, "semi_major_confidence_m")),
            "semiMinorConfidence": units.SEMI_AXIS_LENGTH_CM.to_wire(optional(position, "semi_minor_confidence_m")),
            "semiMajorOrientation": units.heading_enu_rad_to_etsi_tenth_deg(
                optional(position, "semi_major_orientation_rad")),
        },
        "altitude": {
            "altitudeValue": units.ALTITUDE_CM.to_wire(optional(position, "altitude_m")),
            "altitudeConfidence": units.ALTITUDE_CONFIDENCE.to_wire(optional(position, "altitude_confidence_m")),
        },
    }


def reference_position_from_asn(value: dict, position: its_pb2.ReferencePosition) -> None:
    ellipse, altitude = value["positionConfidenceEllipse"], value["altitude"]
    set_optional(position, "latitude_deg", units.LATITUDE_TENTH_MICRODEG.to_si(value["latitude"]))
    set_optional(position, "longitude_deg", units.LONGITUDE_TENTH_MICRODEG.to_si(value["longitude"]))
    set_optional(position, "altitude_m", units.ALTITUDE_CM.to_si(altitude["altitudeValue"]))
    set_optional(position, "altitude_confidence_m", units.ALTITUDE_CONFIDENCE.to_si(altitude["altitudeConfidence"]))
    set_optional(position, "semi_major_confidence_m", units.SEMI_AXIS_LENGTH_CM.to_si(ellipse["semiMajorConfidence"]))
    set_optional(position, "semi_minor_confidence_m", units.SEMI_AXIS_LENGTH_CM.to_si(ellipse["semiMinorConfidence"]))
    set_optional(position, "semi_major_orientation_rad",
                 units.etsi_tenth_deg_to_heading_enu_rad(ellipse["semiMajorOrientation"]))


def path_point_to_asn(point: its_pb2.PathPoint) -> dict:
    value = {"pathPosition": delta_position_to_asn(point)}
    if point.HasField("delta_time_s"):
        value["pathDeltaTime"] = units.PATH_DELTA_TIME_10MS.to_wire(point.delta_time_s)
    return value


def path_point_from_asn(value: dict, point: its_pb2.PathPoint) -> None:
    delta_position_from_asn(value["pathPosition"], point)
    # PathDeltaTime is extensible; a value beyond its root (asn1tools returns raw bytes) has no meaning
    # we know, so that optional field is left absent.
    if isinstance(value.get("pathDeltaTime"), int):
        point.delta_time_s = units.PATH_DELTA_TIME_10MS.to_si(value["pathDeltaTime"])


def delta_position_to_asn(point: its_pb2.PathPoint) -> dict:
    return {
        "deltaLatitude": units.DELTA_LATITUDE_TENTH_MICRODEG.to_wire(optional(point, "delta_latitude_deg")),
        "deltaLongitude": units.DELTA_LONGITUDE_TENTH_MICRODEG.to_wire(optional(point, "delta_longitude_deg")),
        "deltaAltitude": units.DELTA_ALTITUDE_CM.to_wire(optional(point, "delta_altitude_m")),
    }


def delta_position_from_asn(value: dict, point: its_pb2.PathPoint) -> None:
    set_optional(point, "delta_latitude_deg", units.DELTA_LATITUDE_TENTH_MICRODEG.to_si(value["deltaLatitude"]))
    set_optional(point, "delta_longitude_deg", units.DELTA_LONGITUDE_TENTH_MICRODEG.to_si(value["deltaLongitude"]))
    set_optional(point, "delta_altitude_m", units.DELTA_ALTITUDE_CM.to_si(value["deltaAltitude"]))


def speed_to_asn(speed_mps: float | None, confidence_mps: float | None) -> dict:
    return {"speedValue": units.SPEED_CMPS.to_wire(speed_mps),
            "speedConfidence": units.SPEED_CONFIDENCE_CMPS.to_wire(confidence_mps)}


def heading_to_asn(heading_rad: float | None, confidence_rad: float | None) -> dict:
    return {"headingValue": units.heading_enu_rad_to_etsi_tenth_deg(heading_rad),
            "headingConfidence": units.HEADING_CONFIDENCE_TENTH_DEG.to_wire(confidence_rad)}
