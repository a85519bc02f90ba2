"""CAM (EN 302 637-2) asn1tools dict <-> CamContent."""

from __future__ import annotations

from coopdrive.v2x import units
from coopdrive.v2x.mapping.common import (
    EnumTable, bits_to_flags, checked_code, flags_to_bits, heading_to_asn, optional,
    path_point_from_asn, path_point_to_asn, reference_position_from_asn, reference_position_to_asn, set_optional,
    speed_to_asn, wire_protocol_version)
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_GCDC, ItsMessageId
from coopdrive.v2x.timebase import generation_delta_time_ms
from coopdrive.v1 import its_pb2

MAX_STATION_TYPE = 255
MAX_TOLLING_ZONE_ID = 134_217_727
DRIVE_DIRECTION = EnumTable([
    ("forward", its_pb2.DRIVE_DIRECTION_FORWARD), ("backward", its_pb2.DRIVE_DIRECTION_BACKWARD),
    ("unavailable", its_pb2.DRIVE_DIRECTION_UNAVAILABLE)])
CURVATURE_CALCULATION_MODE = EnumTable([
    ("yawRateUsed", its_pb2.CURVATURE_CALCULATION_MODE_YAW_RATE_USED),
    ("yawRateNotUsed", its_pb2.CURVATURE_CALCULATION_MODE_YAW_RATE_NOT_USED),
    ("unavailable", its_pb2.CURVATURE_CALCULATION_MODE_UNAVAILABLE)],
    unknown_extension=its_pb2.CURVATURE_CALCULATION_MODE_UNAVAILABLE)
VEHICLE_LENGTH_CONFIDENCE = EnumTable([
    ("noTrailerPresent", its_pb2.VEHICLE_LENGTH_CONFIDENCE_NO_TRAILER_PRESENT),
    ("trailerPresentWithKnownLength", its_pb2.VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_KNOWN_LENGTH),
    ("trailerPresentWithUnknownLength", its_pb2.VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_UNKNOWN_LENGTH),
    ("trailerPresenceIsUnknown", its_pb2.VEHICLE_LENGTH_CONFIDENCE_TRAILER_PRESENCE_UNKNOWN),
    ("unavailable", its_pb2.VEHICLE_LENGTH_CONFIDENCE_UNAVAILABLE)])
VEHICLE_ROLE = EnumTable([
    ("default", 0), ("publicTransport", 1), ("specialTransport", 2), ("dangerousGoods", 3), ("roadWork", 4),
    ("rescue", 5), ("emergency", 6), ("safetyCar", 7), ("agriculture", 8), ("commercial", 9), ("military", 10),
    ("roadOperator", 11), ("taxi", 12), ("reserved1", 13), ("reserved2", 14), ("reserved3", 15)])
EXTERIOR_LIGHTS = (
    "low_beam_headlights_on", "high_beam_headlights_on", "left_turn_signal_on", "right_turn_signal_on",
    "daytime_running_lights_on", "reverse_light_on", "fog_light_on", "parking_lights_on")
ACCELERATION_CONTROL = (
    "brake_pedal_engaged", "gas_pedal_engaged", "emergency_brake_engaged", "collision_warning_engaged",
    "acc_engaged", "cruise_control_engaged", "speed_limiter_engaged")


class _AccelerationKeys:
    """The wire and protobuf names of one acceleration axis, spelled once rather than per message."""

    def __init__(self, axis: str):
        self.container = f"{axis}Acceleration"
        self.value, self.confidence = f"{axis}AccelerationValue", f"{axis}AccelerationConfidence"
        self.value_field, self.confidence_field = f"{axis}_acceleration_mps2", f"{axis}_acceleration_confidence_mps2"


LONGITUDINAL = _AccelerationKeys("longitudinal")
OPTIONAL_ACCELERATIONS = (_AccelerationKeys("lateral"), _AccelerationKeys("vertical"))


def _curvature_field(protocol_version: int) -> units.LinearField:
    if protocol_version == PROTOCOL_VERSION_GCDC:
        return units.CURVATURE_V1_PER_30000M
    return units.CURVATURE_V2_PER_10000M


def _acceleration_to_asn(hf: its_pb2.CamBasicVehicleHighFrequency, keys: _AccelerationKeys) -> dict:
    return {keys.value: units.ACCELERATION_DECIMPS2.to_wire(optional(hf, keys.value_field)),
            keys.confidence: units.ACCELERATION_CONFIDENCE_DECIMPS2.to_wire(optional(hf, keys.confidence_field))}


def _acceleration_from_asn(value: dict, hf: its_pb2.CamBasicVehicleHighFrequency, keys: _AccelerationKeys) -> None:
    set_optional(hf, keys.value_field, units.ACCELERATION_DECIMPS2.to_si(value[keys.value]))
    set_optional(hf, keys.confidence_field, units.ACCELERATION_CONFIDENCE_DECIMPS2.to_si(value[keys.confidence]))


def cam_to_asn(content: its_pb2.CamContent) -> dict:
    protocol_version = wire_protocol_version(content.protocol_version)
    parameters = {
        "basicContainer": {
            "stationType": checked_code("stationType", content.station_type, 0, MAX_STATION_TYPE),
            "referencePosition": reference_position_to_asn(content.reference_position),
        },
        "highFrequencyContainer": ("rsuContainerHighFrequency", {}),
    }
    if content.HasField("high_frequency"):
        parameters["highFrequencyContainer"] = (
            "basicVehicleContainerHighFrequency", _high_frequency_to_asn(content.high_frequency, protocol_version))
    if content.HasField("low_frequency"):
        low = content.low_frequency
        parameters["lowFrequencyContainer"] = ("basicVehicleContainerLowFrequency", {
            "vehicleRole": VEHICLE_ROLE.to_asn(low.vehicle_role),
            "exteriorLights": flags_to_bits(low.exterior_lights, EXTERIOR_LIGHTS),
            "pathHistory": [path_point_to_asn(point) for point in low.path_history],
        })
    return {
        "header": {"protocolVersion": protocol_version, "messageID": int(ItsMessageId.CAM),
                   "stationID": content.station_id},
        "cam": {"generationDeltaTime": generation_delta_time_ms(content.generation_delta_time_ms),
                "camParameters": parameters},
    }


def _high_frequency_to_asn(hf: its_pb2.CamBasicVehicleHighFrequency, protocol_version: int) -> dict:
    value = {
        "heading": heading_to_asn(optional(hf, "heading_rad"), optional(hf, "heading_confidence_rad")),
        "speed": speed_to_asn(optional(hf, "speed_mps"), optional(hf, "speed_confidence_mps")),
        "driveDirection": DRIVE_DIRECTION.to_asn(hf.drive_direction),
        "vehicleLength": {
            "vehicleLengthValue": units.VEHICLE_LENGTH_DM.to_wire(optional(hf, "vehicle_length_m")),
            "vehicleLengthConfidenceIndication": VEHICLE_LENGTH_CONFIDENCE.to_asn(hf.vehicle_length_confidence)},
        "vehicleWidth": units.VEHICLE_WIDTH_DM.to_wire(optional(hf, "vehicle_width_m")),
        LONGITUDINAL.container: _acceleration_to_asn(hf, LONGITUDINAL),
        "curvature": {
            "curvatureValue": _curvature_field(protocol_version).to_wire(optional(hf, "curvature_per_m")),
            "curvatureConfidence": units.CURVATURE_CONFIDENCE.to_wire(optional(hf, "curvature_confidence_per_m"))},
        "curvatureCalculationMode": CURVATURE_CALCULATION_MODE.to_asn(hf.curvature_calculation_mode),
        "yawRate": {
            "yawRateValue": units.YAW_RATE_CENTIDEGPS.to_wire(optional(hf, "yaw_rate_radps")),
            "yawRateConfidence": units.YAW_RATE_CONFIDENCE.to_wire(optional(hf, "yaw_rate_confidence_radps"))},
    }
    if hf.HasField("acceleration_control"):
        value["accelerationControl"] = flags_to_bits(hf.acceleration_control, ACCELERATION_CONTROL)
    if hf.HasField("lane_position"):
        value["lanePosition"] = min(max(hf.lane_position, -1), 14)
    if hf.HasField("steering_wheel_angle_rad") or hf.HasField("steering_wheel_angle_confidence_rad"):
        value["steeringWheelAngle"] = {
            "steeringWheelAngleValue": units.STEERING_WHEEL_ANGLE_1_5DEG.to_wire(
                optional(hf, "steering_wheel_angle_rad")),
            "steeringWheelAngleConfidence": units.STEERING_WHEEL_ANGLE_CONFIDENCE_1_5DEG.to_wire(
                optional(hf, "steering_wheel_angle_confidence_rad"))}
    for keys in OPTIONAL_ACCELERATIONS:
        if hf.HasField(keys.value_field) or hf.HasField(keys.confidence_field):
            value[keys.container] = _acceleration_to_asn(hf, keys)
    if hf.HasField("performance_class"):
        value["performanceClass"] = min(hf.performance_class, 7)
    if hf.HasField("cen_dsrc_tolling_zone"):
        zone = hf.cen_dsrc_tolling_zone
        value["cenDsrcTollingZone"] = {
            "protectedZoneLatitude": units.LATITUDE_TENTH_MICRODEG.to_wire(zone.latitude_deg),
            "protectedZoneLongitude": units.LONGITUDE_TENTH_MICRODEG.to_wire(zone.longitude_deg)}
        if zone.HasField("zone_id"):
            value["cenDsrcTollingZone"]["cenDsrcTollingZoneID"] = checked_code(
                "cenDsrcTollingZoneID", zone.zone_id, 0, MAX_TOLLING_ZONE_ID)
    return value


def cam_from_asn(value: dict) -> its_pb2.CamContent:
    header, cam = value["header"], value["cam"]
    parameters = cam["camParameters"]
    basic = parameters["basicContainer"]
    content = its_pb2.CamContent(
        protocol_version=header["protocolVersion"], station_id=header["stationID"],
        generation_delta_time_ms=cam["generationDeltaTime"], station_type=basic["stationType"])
    reference_position_from_asn(basic["referencePosition"], content.reference_position)
    kind, hf = parameters["highFrequencyContainer"]
    if kind == "basicVehicleContainerHighFrequency":
        _high_frequency_from_asn(hf, content.high_frequency, header["protocolVersion"])
    if "lowFrequencyContainer" in parameters:
        kind, low = parameters["lowFrequencyContainer"]
        if kind == "basicVehicleContainerLowFrequency":
            content.low_frequency.vehicle_role = VEHICLE_ROLE.to_proto(low["vehicleRole"])
            bits_to_flags(low["exteriorLights"], content.low_frequency.exterior_lights, EXTERIOR_LIGHTS)
            for point in low["pathHistory"]:
                path_point_from_asn(point, content.low_frequency.path_history.add())
    return content


def _high_frequency_from_asn(value: dict, hf: its_pb2.CamBasicVehicleHighFrequency, protocol_version: int) -> None:
    set_optional(hf, "heading_rad", units.etsi_tenth_deg_to_heading_enu_rad(value["heading"]["headingValue"]))
    set_optional(hf, "heading_confidence_rad",
                 units.HEADING_CONFIDENCE_TENTH_DEG.to_si(value["heading"]["headingConfidence"]))
    set_optional(hf, "speed_mps", units.SPEED_CMPS.to_si(value["speed"]["speedValue"]))
    set_optional(hf, "speed_confidence_mps", units.SPEED_CONFIDENCE_CMPS.to_si(value["speed"]["speedConfidence"]))
    hf.drive_direction = DRIVE_DIRECTION.to_proto(value["driveDirection"])
    length = value["vehicleLength"]
    set_optional(hf, "vehicle_length_m", units.VEHICLE_LENGTH_DM.to_si(length["vehicleLengthValue"]))
    hf.vehicle_length_confidence = VEHICLE_LENGTH_CONFIDENCE.to_proto(length["vehicleLengthConfidenceIndication"])
    set_optional(hf, "vehicle_width_m", units.VEHICLE_WIDTH_DM.to_si(value["vehicleWidth"]))
    _acceleration_from_asn(value[LONGITUDINAL.container], hf, LONGITUDINAL)
    for keys in OPTIONAL_ACCELERATIONS:
        if keys.container in value:
            _acceleration_from_asn(value[keys.container], hf, keys)
    curvature = value["curvature"]
    set_optional(hf, "curvature_per_m", _curvature_field(protocol_version).to_si(curvature["curvatureValue"]))
    set_optional(hf, "curvature_confidence_per_m", units.CURVATURE_CONFIDENCE.to_si(curvature["curvatureConfidence"]))
    hf.curvature_calculation_mode = CURVATURE_CALCULATION_MODE.to_proto(value["curvatureCalculationMode"])
    set_optional(hf, "yaw_rate_radps", units.YAW_RATE_CENTIDEGPS.to_si(value["yawRate"]["yawRateValue"]))
    set_optional(hf, "yaw_rate_confidence_radps", units.YAW_RATE_CONFIDENCE.to_si(value["yawRate"]["yawRateConfidence"]))
    if "accelerationControl" in value:
        bits_to_flags(value["accelerationControl"], hf.acceleration_control, ACCELERATION_CONTROL)
    if "lanePosition" in value:
        hf.lane_position = value["lanePosition"]
    if "steeringWheelAngle" in value:
        angle = value["steeringWheelAngle"]
        set_optional(hf, "steering_wheel_angle_rad",
                     units.STEERING_WHEEL_ANGLE_1_5DEG.to_si(angle["steeringWheelAngleValue"]))
        set_optional(hf, "steering_wheel_angle_confidence_rad",
                     units.STEERING_WHEEL_ANGLE_CONFIDENCE_1_5DEG.to_si(angle["steeringWheelAngleConfidence"]))
    if "performanceClass" in value:
        hf.performance_class = value["performanceClass"]
    if "cenDsrcTollingZone" in value:
        zone = value["cenDsrcTollingZone"]
        hf.cen_dsrc_tolling_zone.latitude_deg = units.LATITUDE_TENTH_MICRODEG.to_si(zone["protectedZoneLatitude"]) or 0.0
        hf.cen_dsrc_tolling_zone.longitude_deg = units.LONGITUDE_TENTH_MICRODEG.to_si(zone["protectedZoneLongitude"]) or 0.0
        if "cenDsrcTollingZoneID" in zone:
            hf.cen_dsrc_tolling_zone.zone_id = zone["cenDsrcTollingZoneID"]
