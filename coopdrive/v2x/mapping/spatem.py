"""SPATEM (asn1tools value of TS 103 301's SPATEM) -> SpatemContent: each intersection's status and each signal
group's phases with their end times in seconds of the hour. Advisory speeds, enabled lanes, maneuver assistance
and regional data are not mapped."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.infrastructure import InfrastructureMessage
from coopdrive.v2x.mapping.common import bits_to_flags, flags_to_bits, set_optional
from coopdrive.v2x.mapping.dsrc_common import (
    dsecond_s, enum_code, header_into, header_to_asn, identified_into, identified_to_asn, time_mark_s,
    time_mark_to_asn)
from coopdrive.v1 import infrastructure_pb2 as pb

# MovementPhaseState names in wire-code order (the protobuf enum's numbers are the codes).
MOVEMENT_PHASE_STATES = (
    "unavailable", "dark", "stop-Then-Proceed", "stop-And-Remain", "pre-Movement", "permissive-Movement-Allowed",
    "protected-Movement-Allowed", "permissive-clearance", "protected-clearance", "caution-Conflicting-Traffic")
# IntersectionStatusObject bits 0..13, as IntersectionStatus fields.
INTERSECTION_STATUS_BITS = (
    "manual_control_is_enabled", "stop_time_is_activated", "failure_flash", "preempt_is_active",
    "signal_priority_is_active", "fixed_time_operation", "traffic_dependent_operation", "standby_operation",
    "failure_mode", "off", "recent_map_message_update", "recent_change_in_map_assigned_lanes_ids_used",
    "no_valid_map_is_available_at_this_time", "no_valid_spat_is_available_at_this_time")
# IntersectionStatusObject is 16 bits, of which the standard names the first 14.
STATUS_BITS = 16
# TimeChangeDetails fields holding a TimeMark, and where each goes.
_TIME_MARKS = (("startTime", "start_time_s"), ("minEndTime", "min_end_time_s"), ("maxEndTime", "max_end_time_s"),
               ("likelyTime", "likely_time_s"), ("nextTime", "next_time_s"))


def spatem_from_asn(value: dict) -> pb.SpatemContent:
    content = pb.SpatemContent()
    header_into(value, content)
    spat = value["spat"]
    set_optional(content, "minute_of_year", spat.get("timeStamp"))
    content.name = spat.get("name", "")
    for state in spat["intersections"]:
        _intersection_into(state, content.intersections.add())
    return content


def _intersection_into(value: dict, intersection: pb.SpatIntersection) -> None:
    identified_into(value, intersection)
    bits_to_flags(value["status"], intersection.status, INTERSECTION_STATUS_BITS)
    set_optional(intersection, "minute_of_year", value.get("moy"))
    set_optional(intersection, "second_of_minute_s", dsecond_s(value.get("timeStamp")))
    for movement in value["states"]:
        group = intersection.signal_groups.add(signal_group=movement["signalGroup"],
                                               movement_name=movement.get("movementName", ""))
        for event in movement["state-time-speed"]:
            _event_into(event, group.events.add())


def _event_into(value: dict, event: pb.MovementEvent) -> None:
    event.state = enum_code(MOVEMENT_PHASE_STATES, value["eventState"])
    timing = value.get("timing")
    if timing is None:
        return
    for wire_name, field in _TIME_MARKS:
        set_optional(event, field, time_mark_s(timing.get(wire_name)))
    set_optional(event, "confidence", timing.get("confidence"))


def spatem_to_asn(content: pb.SpatemContent) -> dict:
    """The asn1tools value of a SPATEM (what the simulator's roadside unit sends); times in seconds of the hour."""
    spat: dict = {"intersections": [_intersection_to_asn(i) for i in content.intersections]}
    if content.HasField("minute_of_year"):
        spat["timeStamp"] = content.minute_of_year
    if content.name:
        spat["name"] = content.name
    return {"header": header_to_asn(content, InfrastructureMessage.SPATEM.message_id), "spat": spat}


def _intersection_to_asn(intersection: pb.SpatIntersection) -> dict:
    value = identified_to_asn(intersection)
    status, _ = flags_to_bits(intersection.status, INTERSECTION_STATUS_BITS)
    value["status"] = (status, STATUS_BITS)
    if intersection.HasField("minute_of_year"):
        value["moy"] = intersection.minute_of_year
    if intersection.HasField("second_of_minute_s"):
        value["timeStamp"] = units.DSECOND_MS.to_wire(intersection.second_of_minute_s)
    value["states"] = [_group_to_asn(group) for group in intersection.signal_groups]
    return value


def _group_to_asn(group: pb.SignalGroupState) -> dict:
    value = {"signalGroup": group.signal_group, "state-time-speed": [_event_to_asn(e) for e in group.events]}
    if group.movement_name:
        value["movementName"] = group.movement_name
    return value


def _event_to_asn(event: pb.MovementEvent) -> dict:
    value: dict = {"eventState": MOVEMENT_PHASE_STATES[event.state]}
    if not event.HasField("min_end_time_s"):
        return value
    # minEndTime is the one time TimeChangeDetails must carry; the others go when known.
    timing = {wire_name: time_mark_to_asn(getattr(event, field)) for wire_name, field in _TIME_MARKS
              if event.HasField(field)}
    if event.HasField("confidence"):
        timing["confidence"] = event.confidence
    value["timing"] = timing
    return value
