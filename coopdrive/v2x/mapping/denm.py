"""DENM (EN 302 637-3) asn1tools dict <-> DenmContent."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.mapping.common import (
    EnumTable, bits_to_bools, bools_to_bits, delta_position_from_asn, delta_position_to_asn, heading_to_asn,
    optional, path_point_from_asn, path_point_to_asn, reference_position_from_asn, reference_position_to_asn,
    set_optional, speed_to_asn, wire_protocol_version)
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_CURRENT, PROTOCOL_VERSION_GCDC, ItsMessageId
from coopdrive.v1 import its_pb2

# ETSI EN 302 637-3: a DENM without a validity duration is valid for 600 s.
DEFAULT_VALIDITY_DURATION_S = 600.0
TERMINATION = EnumTable([("isCancellation", its_pb2.DENM_TERMINATION_CANCELLATION),
                         ("isNegation", its_pb2.DENM_TERMINATION_NEGATION)])
RELEVANCE_DISTANCE = EnumTable([
    (name, index + 1) for index, name in enumerate((
        "lessThan50m", "lessThan100m", "lessThan200m", "lessThan500m", "lessThan1000m", "lessThan5km",
        "lessThan10km", "over10km"))])
RELEVANCE_TRAFFIC_DIRECTION = EnumTable([
    (name, index + 1) for index, name in enumerate((
        "allTrafficDirections", "upstreamTraffic", "downstreamTraffic", "oppositeTraffic"))])
ROAD_TYPE = EnumTable([
    (name, index + 1) for index, name in enumerate((
        "urban-NoStructuralSeparationToOppositeLanes", "urban-WithStructuralSeparationToOppositeLanes",
        "nonUrban-NoStructuralSeparationToOppositeLanes", "nonUrban-WithStructuralSeparationToOppositeLanes"))])
HARD_SHOULDER_STATUS = EnumTable([
    (name, index + 1) for index, name in enumerate(("availableForStopping", "closed", "availableForDriving"))])
POSITIONING_SOLUTION = EnumTable([
    (name, index) for index, name in enumerate((
        "noPositioningSolution", "sGNSS", "dGNSS", "sGNSSplusDR", "dGNSSplusDR", "dR"))])
MAX_LANE_POSITION = 14
MIN_LANE_POSITION = -1
# ClosedLanes changed in CDD v1.3.1: the hard shoulder became the "outer" one and lanes count 13 bits.
HARD_SHOULDER_KEY = {PROTOCOL_VERSION_GCDC: "hardShoulderStatus", PROTOCOL_VERSION_CURRENT: "outerhardShoulderStatus"}
MAX_DRIVING_LANE_BITS = {PROTOCOL_VERSION_GCDC: 14, PROTOCOL_VERSION_CURRENT: 13}


def _cause_to_asn(cause: its_pb2.CauseCode) -> dict:
    return {"causeCode": min(cause.cause_code, 255), "subCauseCode": min(cause.sub_cause_code, 255)}


def _cause_from_asn(value: dict, cause: its_pb2.CauseCode) -> None:
    cause.cause_code, cause.sub_cause_code = value["causeCode"], value["subCauseCode"]


def denm_to_asn(content: its_pb2.DenmContent) -> dict:
    protocol_version = wire_protocol_version(content.protocol_version)
    management = {
        "actionID": {"originatingStationID": content.originating_station_id,
                     "sequenceNumber": content.sequence_number},
        "detectionTime": content.detection_time_tai_ms,
        "referenceTime": content.reference_time_tai_ms,
        "eventPosition": reference_position_to_asn(content.event_position),
        "validityDuration": units.VALIDITY_DURATION_S.to_wire(content.validity_duration_s),
        "stationType": int(content.station_type),
    }
    if content.termination != its_pb2.DENM_TERMINATION_NONE:
        management["termination"] = TERMINATION.to_asn(content.termination)
    if content.relevance_distance:
        management["relevanceDistance"] = RELEVANCE_DISTANCE.to_asn(content.relevance_distance)
    if content.relevance_traffic_direction:
        management["relevanceTrafficDirection"] = RELEVANCE_TRAFFIC_DIRECTION.to_asn(
            content.relevance_traffic_direction)
    if content.HasField("transmission_interval_s"):
        management["transmissionInterval"] = units.TRANSMISSION_INTERVAL_MS.to_wire(content.transmission_interval_s)
    denm = {"management": management}
    if content.HasField("situation"):
        denm["situation"] = _situation_to_asn(content.situation)
    if content.HasField("location"):
        denm["location"] = _location_to_asn(content.location)
    if content.HasField("alacarte"):
        denm["alacarte"] = _alacarte_to_asn(content.alacarte, protocol_version)
    return {
        "header": {"protocolVersion": protocol_version, "messageID": int(ItsMessageId.DENM),
                   "stationID": content.station_id},
        "denm": denm,
    }


def _situation_to_asn(situation: its_pb2.DenmSituation) -> dict:
    value = {"informationQuality": min(situation.information_quality, 7),
             "eventType": _cause_to_asn(situation.event_type)}
    if situation.HasField("linked_cause"):
        value["linkedCause"] = _cause_to_asn(situation.linked_cause)
    if situation.event_history:
        value["eventHistory"] = [_event_point_to_asn(point) for point in situation.event_history]
    return value


def _event_point_to_asn(point: its_pb2.EventPoint) -> dict:
    value = {"eventPosition": delta_position_to_asn(point.position),
             "informationQuality": min(point.information_quality, 7)}
    if point.position.HasField("delta_time_s"):
        value["eventDeltaTime"] = units.PATH_DELTA_TIME_10MS.to_wire(point.position.delta_time_s)
    return value


def _location_to_asn(location: its_pb2.DenmLocation) -> dict:
    value = {"traces": [[path_point_to_asn(point) for point in trace.points] for trace in location.traces]}
    if location.HasField("event_speed_mps") or location.HasField("event_speed_confidence_mps"):
        value["eventSpeed"] = speed_to_asn(
            optional(location, "event_speed_mps"), optional(location, "event_speed_confidence_mps"))
    if location.HasField("event_position_heading_rad") or location.HasField("event_position_heading_confidence_rad"):
        value["eventPositionHeading"] = heading_to_asn(
            optional(location, "event_position_heading_rad"),
            optional(location, "event_position_heading_confidence_rad"))
    if location.road_type:
        value["roadType"] = ROAD_TYPE.to_asn(location.road_type)
    return value


def _alacarte_to_asn(alacarte: its_pb2.DenmAlacarte, protocol_version: int) -> dict:
    value = {}
    if alacarte.HasField("lane_position"):
        value["lanePosition"] = min(max(alacarte.lane_position, MIN_LANE_POSITION), MAX_LANE_POSITION)
    if alacarte.HasField("external_temperature_c"):
        value["externalTemperature"] = units.TEMPERATURE_DEGC.to_wire(alacarte.external_temperature_c)
    if alacarte.HasField("road_works"):
        works, road_works = alacarte.road_works, {}
        if works.HasField("light_bar_activated") or works.HasField("siren_activated"):
            road_works["lightBarSirenInUse"] = bools_to_bits([works.light_bar_activated, works.siren_activated])
        if works.HasField("closed_lanes"):
            lanes = works.closed_lanes.driving_lane_closed[:MAX_DRIVING_LANE_BITS[protocol_version]] or [False]
            road_works["closedLanes"] = {"drivingLaneStatus": bools_to_bits(list(lanes))}
            if works.closed_lanes.hard_shoulder_status:
                road_works["closedLanes"][HARD_SHOULDER_KEY[protocol_version]] = HARD_SHOULDER_STATUS.to_asn(
                    works.closed_lanes.hard_shoulder_status)
        if works.HasField("speed_limit_mps"):
            road_works["speedLimit"] = units.SPEED_LIMIT_KPH.to_wire(works.speed_limit_mps)
        value["roadWorks"] = road_works
    if alacarte.HasField("positioning_solution"):
        value["positioningSolution"] = POSITIONING_SOLUTION.to_asn(alacarte.positioning_solution)
    return value


def _validity_duration(management: dict) -> int:
    """validityDuration, or its DEFAULT when left out (canonical UPER omits a DEFAULT value): asn1tools then
    fills in the value reference's name ('defaultValidity'), not its number."""
    value = management.get("validityDuration")
    return value if isinstance(value, int) else round(DEFAULT_VALIDITY_DURATION_S)


def denm_from_asn(value: dict) -> its_pb2.DenmContent:
    header, denm = value["header"], value["denm"]
    management = denm["management"]
    content = its_pb2.DenmContent(
        protocol_version=header["protocolVersion"], station_id=header["stationID"],
        originating_station_id=management["actionID"]["originatingStationID"],
        sequence_number=management["actionID"]["sequenceNumber"],
        detection_time_tai_ms=management["detectionTime"], reference_time_tai_ms=management["referenceTime"],
        validity_duration_s=units.VALIDITY_DURATION_S.to_si(_validity_duration(management)),
        station_type=management["stationType"])
    reference_position_from_asn(management["eventPosition"], content.event_position)
    if "termination" in management:
        content.termination = TERMINATION.to_proto(management["termination"])
    if "relevanceDistance" in management:
        content.relevance_distance = RELEVANCE_DISTANCE.to_proto(management["relevanceDistance"])
    if "relevanceTrafficDirection" in management:
        content.relevance_traffic_direction = RELEVANCE_TRAFFIC_DIRECTION.to_proto(
            management["relevanceTrafficDirection"])
    if "transmissionInterval" in management:
        content.transmission_interval_s = units.TRANSMISSION_INTERVAL_MS.to_si(management["transmissionInterval"])
    if "situation" in denm:
        _situation_from_asn(denm["situation"], content.situation)
    if "location" in denm:
        _location_from_asn(denm["location"], content.location)
    if "alacarte" in denm:
        _alacarte_from_asn(denm["alacarte"], content.alacarte)
    return content


def _situation_from_asn(value: dict, situation: its_pb2.DenmSituation) -> None:
    situation.information_quality = value["informationQuality"]
    _cause_from_asn(value["eventType"], situation.event_type)
    if "linkedCause" in value:
        _cause_from_asn(value["linkedCause"], situation.linked_cause)
    for point_value in value.get("eventHistory", []):
        point = situation.event_history.add(information_quality=point_value["informationQuality"])
        delta_position_from_asn(point_value["eventPosition"], point.position)
        if isinstance(point_value.get("eventDeltaTime"), int):
            point.position.delta_time_s = units.PATH_DELTA_TIME_10MS.to_si(point_value["eventDeltaTime"])


def _location_from_asn(value: dict, location: its_pb2.DenmLocation) -> None:
    for trace_value in value["traces"]:
        trace = location.traces.add()
        for point in trace_value:
            path_point_from_asn(point, trace.points.add())
    if "eventSpeed" in value:
        set_optional(location, "event_speed_mps", units.SPEED_CMPS.to_si(value["eventSpeed"]["speedValue"]))
        set_optional(location, "event_speed_confidence_mps",
                     units.SPEED_CONFIDENCE_CMPS.to_si(value["eventSpeed"]["speedConfidence"]))
    if "eventPositionHeading" in value:
        heading = value["eventPositionHeading"]
        set_optional(location, "event_position_heading_rad",
                     units.etsi_tenth_deg_to_heading_enu_rad(heading["headingValue"]))
        set_optional(location, "event_position_heading_confidence_rad",
                     units.HEADING_CONFIDENCE_TENTH_DEG.to_si(heading["headingConfidence"]))
    if "roadType" in value:
        location.road_type = ROAD_TYPE.to_proto(value["roadType"])


def _alacarte_from_asn(value: dict, alacarte: its_pb2.DenmAlacarte) -> None:
    alacarte.SetInParent()
    if "lanePosition" in value:
        alacarte.lane_position = value["lanePosition"]
    if "externalTemperature" in value:
        alacarte.external_temperature_c = units.TEMPERATURE_DEGC.to_si(value["externalTemperature"])
    if "roadWorks" in value:
        works_value, works = value["roadWorks"], alacarte.road_works
        works.SetInParent()
        if "lightBarSirenInUse" in value["roadWorks"]:
            works.light_bar_activated, works.siren_activated = bits_to_bools(works_value["lightBarSirenInUse"])[:2]
        if "closedLanes" in works_value:
            lanes = works_value["closedLanes"]
            works.closed_lanes.SetInParent()
            works.closed_lanes.driving_lane_closed.extend(bits_to_bools(lanes.get("drivingLaneStatus", (b"", 0))))
            shoulder = lanes.get("hardShoulderStatus", lanes.get("outerhardShoulderStatus"))
            if shoulder is not None:
                works.closed_lanes.hard_shoulder_status = HARD_SHOULDER_STATUS.to_proto(shoulder)
        if "speedLimit" in works_value:
            works.speed_limit_mps = units.SPEED_LIMIT_KPH.to_si(works_value["speedLimit"])
    if value.get("positioningSolution") is not None:  # None: an extension value newer than our schema
        alacarte.positioning_solution = POSITIONING_SOLUTION.to_proto(value["positioningSolution"])
