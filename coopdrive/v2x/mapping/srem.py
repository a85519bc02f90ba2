"""SREM (asn1tools value of TS 103 301's SREM) -> SremContent: who asks which intersection for priority, from
which lane. The requestor's position, transit data and regional data are not mapped."""

from __future__ import annotations

from coopdrive.v2x.mapping.dsrc_common import (
    access_point_into, enum_code, header_into, intersection_into, stamp_into, vehicle_id_into)
from coopdrive.v1 import infrastructure_pb2 as pb

PRIORITY_REQUEST_TYPES = ("priorityRequestTypeReserved", "priorityRequest", "priorityRequestUpdate",
                          "priorityCancellation")
# BasicVehicleRole names in wire-code order (tram, 23, was added in TS 103 301 v2.2.1).
BASIC_VEHICLE_ROLES = (
    "basicVehicle", "publicTransport", "specialTransport", "dangerousGoods", "roadWork", "roadRescue", "emergency",
    "safetyCar", "none-unknown", "truck", "motorcycle", "roadSideSource", "police", "fire", "ambulance", "dot",
    "transit", "slowMoving", "stopNgo", "cyclist", "pedestrian", "nonMotorized", "military", "tram")


def srem_from_asn(value: dict) -> pb.SremContent:
    content = pb.SremContent()
    header_into(value, content)
    request_message = value["srm"]
    stamp_into(request_message, content)
    for package in request_message.get("requests", ()):
        _request_into(package["request"], content.requests.add())
    requestor = request_message["requestor"]
    vehicle_id_into(requestor["id"], content.requestor)
    role_into(requestor.get("type", {}).get("role"), content.requestor)
    return content


def role_into(name: str | None, requestor: pb.Requestor) -> None:
    """BasicVehicleRole's code, when the role is given and known to our module."""
    if name in BASIC_VEHICLE_ROLES:
        requestor.role = BASIC_VEHICLE_ROLES.index(name)


def _request_into(value: dict, request: pb.SignalRequest) -> None:
    intersection_into(value["id"], request.intersection)
    request.request_id = value["requestID"]
    request.request_type = enum_code(PRIORITY_REQUEST_TYPES, value["requestType"])
    access_point_into(value["inBoundLane"], request.inbound)
    if "outBoundLane" in value:
        access_point_into(value["outBoundLane"], request.outbound)
