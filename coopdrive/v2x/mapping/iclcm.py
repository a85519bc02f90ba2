"""iCLCM (GCDC 2016 i-GAME Cooperative Lane Change Message) asn1tools dict <-> IclcmContent."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_GCDC, ItsMessageId
from coopdrive.v2x.mapping.common import checked_code, optional, set_optional
from coopdrive.v2x.timebase import generation_delta_time_ms
from coopdrive.v1 import its_pb2

END_OF_SCENARIO = 1
MAX_PLATOON_ID = 255
MAX_COUNTER_INTERSECTION = 3
MIN_INTENTION, MAX_INTENTION = 1, 3
MAX_CONTROLLER_TYPE = 3
MAX_START_PLATOON = 1
MERGE_FLAGS = (
    ("mergeRequest", "merge_request"), ("mergeSafeToMerge", "merge_safe_to_merge"), ("mergeFlag", "merge_flag"),
    ("mergeFlagTail", "merge_flag_tail"), ("mergeFlagHead", "merge_flag_head"))


def iclcm_to_asn(content: its_pb2.IclcmContent) -> dict:
    parameters = {
        "vehicleContainerHighFrequency": {
            "vehicleRearAxleLocation": units.ICLCM_REAR_AXLE_LOCATION_CM.to_wire(content.rear_axle_location_m),
            "controllerType": checked_code("controllerType", content.controller_type, 0, MAX_CONTROLLER_TYPE),
            "vehicleResponseTime": {
                "vehicleResponseTimeConstant": units.ICLCM_RESPONSE_TIME_10MS.to_wire(
                    optional(content, "response_time_constant_s")),
                "vehicleResponseTimeDelay": units.ICLCM_RESPONSE_TIME_10MS.to_wire(
                    optional(content, "response_time_delay_s"))},
            "targetLongitudinalAcceleration": units.ICLCM_TARGET_ACCELERATION_CMPS2.to_wire(
                optional(content, "target_longitudinal_acceleration_mps2")),
            "timeHeadway": units.ICLCM_TIME_HEADWAY_100MS.to_wire(optional(content, "time_headway_s")),
            "cruisespeed": units.ICLCM_CRUISE_SPEED_CMPS.to_wire(optional(content, "cruise_speed_mps")),
        },
        "mostImportantObjectContainer": {
            "mioID": content.mio_id,
            "mioRange": units.ICLCM_MIO_RANGE_CM.to_wire(optional(content, "mio_range_m")),
            "mioBearing": units.ICLCM_MIO_BEARING_2MRAD_RIGHT.to_wire(optional(content, "mio_bearing_rad")),
            "mioRangeRate": units.ICLCM_MIO_RANGE_RATE_CMPS.to_wire(optional(content, "mio_range_rate_mps")),
        },
        "laneObject": {"lane": units.ICLCM_LANE.to_wire(optional(content, "lane"))},
        "pairIdObject": {"forwardID": content.forward_id, "backwardID": content.backward_id,
                         "acknowledgeFlag": int(content.acknowledge_flag)},
        "mergeObject": {wire: int(getattr(content, field)) for wire, field in MERGE_FLAGS},
        "scenarioObject": {
            "platoonID": min(content.platoon_id, MAX_PLATOON_ID),
            "distanceTravelledCZ": units.ICLCM_DISTANCE_TRAVELLED_CZ_DM.to_wire(content.distance_travelled_cz_m),
            "intention": min(max(int(content.intention), MIN_INTENTION), MAX_INTENTION),
            "counterIntersection": min(content.counter_intersection, MAX_COUNTER_INTERSECTION),
        },
    }
    if content.has_low_frequency:
        low = {}
        if content.HasField("participants_ready"):
            low["participantsReady"] = int(content.participants_ready)
        if content.HasField("start_platoon"):
            low["startPlatoon"] = checked_code("startPlatoon", content.start_platoon, 0, MAX_START_PLATOON)
        if content.end_of_scenario:
            low["endOfScenario"] = END_OF_SCENARIO
        parameters["lowFrequencyContainer"] = low
    return {
        "header": {"protocolVersion": PROTOCOL_VERSION_GCDC, "messageID": int(ItsMessageId.ICLCM),
                   "stationID": content.station_id},
        "iclm": {"generationDeltaTime": generation_delta_time_ms(content.generation_delta_time_ms),
                 "iclmParameters": parameters},
    }


def iclcm_from_asn(value: dict) -> its_pb2.IclcmContent:
    header, body = value["header"], value["iclm"]
    parameters = body["iclmParameters"]
    hf = parameters["vehicleContainerHighFrequency"]
    mio = parameters["mostImportantObjectContainer"]
    pair = parameters["pairIdObject"]
    scenario = parameters["scenarioObject"]
    content = its_pb2.IclcmContent(
        protocol_version=header["protocolVersion"], station_id=header["stationID"],
        generation_delta_time_ms=body["generationDeltaTime"],
        rear_axle_location_m=units.ICLCM_REAR_AXLE_LOCATION_CM.to_si(hf["vehicleRearAxleLocation"]),
        controller_type=hf["controllerType"],
        mio_id=mio["mioID"], forward_id=pair["forwardID"], backward_id=pair["backwardID"],
        acknowledge_flag=bool(pair["acknowledgeFlag"]),
        platoon_id=scenario["platoonID"],
        distance_travelled_cz_m=units.ICLCM_DISTANCE_TRAVELLED_CZ_DM.to_si(scenario["distanceTravelledCZ"]),
        intention=scenario["intention"], counter_intersection=scenario["counterIntersection"])
    response = hf["vehicleResponseTime"]
    set_optional(content, "response_time_constant_s",
                 units.ICLCM_RESPONSE_TIME_10MS.to_si(response["vehicleResponseTimeConstant"]))
    set_optional(content, "response_time_delay_s",
                 units.ICLCM_RESPONSE_TIME_10MS.to_si(response["vehicleResponseTimeDelay"]))
    set_optional(content, "target_longitudinal_acceleration_mps2",
                 units.ICLCM_TARGET_ACCELERATION_CMPS2.to_si(hf["targetLongitudinalAcceleration"]))
    set_optional(content, "time_headway_s", units.ICLCM_TIME_HEADWAY_100MS.to_si(hf["timeHeadway"]))
    set_optional(content, "cruise_speed_mps", units.ICLCM_CRUISE_SPEED_CMPS.to_si(hf["cruisespeed"]))
    set_optional(content, "mio_range_m", units.ICLCM_MIO_RANGE_CM.to_si(mio["mioRange"]))
    set_optional(content, "mio_bearing_rad", units.ICLCM_MIO_BEARING_2MRAD_RIGHT.to_si(mio["mioBearing"]))
    set_optional(content, "mio_range_rate_mps", units.ICLCM_MIO_RANGE_RATE_CMPS.to_si(mio["mioRangeRate"]))
    lane = units.ICLCM_LANE.to_si(parameters["laneObject"]["lane"])
    if lane is not None:
        content.lane = int(lane)
    for wire, field in MERGE_FLAGS:
        setattr(content, field, bool(parameters["mergeObject"][wire]))
    if "lowFrequencyContainer" in parameters:
        low = parameters["lowFrequencyContainer"]
        content.has_low_frequency = True
        if "participantsReady" in low:
            content.participants_ready = bool(low["participantsReady"])
        if "startPlatoon" in low:
            content.start_platoon = low["startPlatoon"]
        content.end_of_scenario = "endOfScenario" in low
    return content
