"""Pieces the MAPEM, SPATEM, SREM and SSEM mappings share: intersection ids, access points, requestors, times.

asn1tools' value forms: CHOICE (name, value), with (None, None) for an alternative added after our module;
ENUMERATED a name, None for a value added after it; BIT STRING (bytes, nbits).
"""

from __future__ import annotations

from google.protobuf.message import Message

from coopdrive.v2x import units
from coopdrive.v2x.mapping.common import set_optional
from coopdrive.v1 import infrastructure_pb2


def header_into(value: dict, content: Message) -> None:
    """ItsPduHeader (ETSI-ITS-CDD field names) into a content message's protocol_version and station_id."""
    header = value["header"]
    content.protocol_version, content.station_id = header["protocolVersion"], header["stationId"]


def header_to_asn(content: Message, message_id: int) -> dict:
    """A content message's protocol_version and station_id as the ItsPduHeader of an infrastructure message."""
    return {"protocolVersion": content.protocol_version, "messageId": message_id, "stationId": content.station_id}


def intersection_to_asn(reference: infrastructure_pb2.IntersectionReference) -> dict:
    value = {"id": reference.id}
    if reference.HasField("region"):
        value["region"] = reference.region
    return value


def identified_to_asn(intersection: Message) -> dict:
    """The id, revision and (when set) name of a MAPEM's IntersectionGeometry or a SPATEM's IntersectionState."""
    value = {"id": intersection_to_asn(intersection.id), "revision": intersection.revision}
    if intersection.name:
        value["name"] = intersection.name
    return value


def intersection_into(value: dict, reference: infrastructure_pb2.IntersectionReference) -> None:
    """IntersectionReferenceID."""
    reference.id = value["id"]
    set_optional(reference, "region", value.get("region"))


def identified_into(value: dict, intersection: Message) -> None:
    """A MAPEM's IntersectionGeometry or a SPATEM's IntersectionState: id, revision and name."""
    intersection_into(value["id"], intersection.id)
    intersection.revision = value["revision"]
    intersection.name = value.get("name", "")


def stamp_into(value: dict, content: Message) -> None:
    """An SREM's or SSEM's time stamp (minute of the year, DSecond) and sequence number."""
    set_optional(content, "minute_of_year", value.get("timeStamp"))
    set_optional(content, "second_of_minute_s", dsecond_s(value["second"]))
    set_optional(content, "sequence_number", value.get("sequenceNumber"))


def time_mark_s(value: int | None) -> float | None:
    """TimeMark (0.1 s after the start of the hour) in seconds; None when absent or unknown (36001)."""
    return None if value is None else units.TIME_MARK_DS.to_si(value)


def time_mark_to_asn(seconds_of_hour: float | None) -> int:
    """Seconds after the start of the hour as a TimeMark (tenths); None is unknown (36001)."""
    return units.TIME_MARK_DS.to_wire(seconds_of_hour)


def dsecond_s(value: int | None) -> float | None:
    return None if value is None else units.DSECOND_MS.to_si(value)


def access_point_into(value: tuple, point: infrastructure_pb2.AccessPoint) -> None:
    """IntersectionAccessPoint: lane, approach or connection (an unknown alternative leaves it empty)."""
    name, number = value
    field = {"lane": "lane_id", "approach": "approach_id", "connection": "connection_id"}.get(name)
    if field is not None:
        setattr(point, field, number)


def vehicle_id_into(value: tuple, requestor: infrastructure_pb2.Requestor) -> None:
    """VehicleID: a StationID, or a TemporaryID (4 octets, read as a big-endian integer)."""
    name, number = value
    if name == "stationID":
        requestor.station_id = number
    else:
        requestor.temporary_id = int.from_bytes(number, "big")


def enum_code(names: tuple[str, ...], name: str | None) -> int:
    """An ENUMERATED name's code, for protobuf enums whose numbers equal the wire codes; a value added after our
    module (None) is code 0, each of these enums' 'unknown' or 'unavailable'."""
    return names.index(name) if name is not None else 0
