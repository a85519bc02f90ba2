"""SSEM (asn1tools value of TS 103 301's SSEM) -> SsemContent: each intersection's answer to the signal requests
it holds. Regional data are not mapped."""

from __future__ import annotations

from coopdrive.v2x.mapping.dsrc_common import (
    access_point_into, enum_code, header_into, intersection_into, stamp_into, vehicle_id_into)
from coopdrive.v2x.mapping.srem import role_into
from coopdrive.v1 import infrastructure_pb2 as pb

PRIORITIZATION_RESPONSES = ("unknown", "requested", "processing", "watchOtherTraffic", "granted", "rejected",
                            "maxPresence", "reserviceLocked")


def ssem_from_asn(value: dict) -> pb.SsemContent:
    content = pb.SsemContent()
    header_into(value, content)
    status_message = value["ssm"]
    stamp_into(status_message, content)
    for status in status_message["status"]:
        intersection = content.intersections.add(sequence_number=status["sequenceNumber"])
        intersection_into(status["id"], intersection.intersection)
        for package in status["sigStatus"]:
            _entry_into(package, intersection.entries.add())
    return content


def _entry_into(value: dict, entry: pb.SignalStatusEntry) -> None:
    requester = value.get("requester")
    if requester is not None:
        vehicle_id_into(requester["id"], entry.requester)
        role_into(requester.get("role"), entry.requester)
        entry.request_id = requester["request"]
    access_point_into(value["inboundOn"], entry.inbound)
    if "outboundOn" in value:
        access_point_into(value["outboundOn"], entry.outbound)
    entry.status = enum_code(PRIORITIZATION_RESPONSES, value["status"])
