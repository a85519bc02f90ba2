"""Content messages with every field at the top or bottom of its wire range, shared by the v2x tests."""

import math

from google.protobuf.json_format import MessageToDict

from coopdrive.v1 import its_pb2

MAX_STATION_ID = 2**32 - 1
MAX_TIMESTAMP_ITS_MS = 2**42 - 1
ETSI_MAX_HEADING_AS_ENU_RAD = math.radians(90.0 - 359.9 + 360.0)
ETSI_NORTH_AS_ENU_RAD = math.pi / 2


def flatten(message) -> dict:
    """field path -> value, for comparing messages with a tolerance on floats."""
    flat = {}

    def walk(prefix, value):
        if isinstance(value, dict):
            for key, item in value.items():
                walk(f"{prefix}.{key}", item)
        elif isinstance(value, list):
            flat[f"{prefix}#"] = len(value)
            for index, item in enumerate(value):
                walk(f"{prefix}[{index}]", item)
        else:
            flat[prefix] = value
    walk("", MessageToDict(message, preserving_proto_field_name=True, use_integers_for_enums=True))
    return flat


def position(top: bool) -> its_pb2.ReferencePosition:
    if top:
        return its_pb2.ReferencePosition(
            latitude_deg=90.0, longitude_deg=180.0, altitude_m=8000.0, semi_major_confidence_m=40.93,
            semi_minor_confidence_m=40.93, semi_major_orientation_rad=ETSI_MAX_HEADING_AS_ENU_RAD,
            altitude_confidence_m=200.0)
    return its_pb2.ReferencePosition(
        latitude_deg=-90.0, longitude_deg=-180.0, altitude_m=-1000.0, semi_major_confidence_m=0.0,
        semi_minor_confidence_m=0.0, semi_major_orientation_rad=ETSI_NORTH_AS_ENU_RAD, altitude_confidence_m=0.01)


def path_point(top: bool) -> its_pb2.PathPoint:
    sign = 1 if top else -1
    return its_pb2.PathPoint(delta_latitude_deg=sign * 0.0131071, delta_longitude_deg=sign * 0.0131071,
                             delta_altitude_m=127.99 if top else -127.0, delta_time_s=655.35 if top else 0.01)


def cam(top: bool, protocol_version: int = 1) -> its_pb2.CamContent:
    sign = 1 if top else -1
    curvature_per_m = (1.0 if protocol_version == 1 else 0.1022) if top else (-1.0 if protocol_version == 1 else -0.1023)
    hf = its_pb2.CamBasicVehicleHighFrequency(
        heading_rad=ETSI_MAX_HEADING_AS_ENU_RAD if top else ETSI_NORTH_AS_ENU_RAD,
        heading_confidence_rad=math.radians(12.5 if top else 0.1),
        speed_mps=163.82 if top else 0.0, speed_confidence_mps=1.25 if top else 0.01,
        drive_direction=its_pb2.DRIVE_DIRECTION_BACKWARD if top else its_pb2.DRIVE_DIRECTION_FORWARD,
        vehicle_length_m=102.1 if top else 0.1,
        vehicle_length_confidence=its_pb2.VEHICLE_LENGTH_CONFIDENCE_TRAILER_PRESENCE_UNKNOWN if top
        else its_pb2.VEHICLE_LENGTH_CONFIDENCE_NO_TRAILER_PRESENT,
        vehicle_width_m=6.0 if top else 0.1,
        longitudinal_acceleration_mps2=sign * 16.0, longitudinal_acceleration_confidence_mps2=10.0 if top else 0.0,
        curvature_per_m=curvature_per_m, curvature_confidence_per_m=0.1 if top else 0.00002,
        curvature_calculation_mode=its_pb2.CURVATURE_CALCULATION_MODE_YAW_RATE_NOT_USED if top
        else its_pb2.CURVATURE_CALCULATION_MODE_YAW_RATE_USED,
        yaw_rate_radps=sign * math.radians(327.66), yaw_rate_confidence_radps=math.radians(100.0 if top else 0.01),
        lane_position=14 if top else -1,
        steering_wheel_angle_rad=sign * math.radians(1.5 * 511),
        steering_wheel_angle_confidence_rad=math.radians(1.5 * (125 if top else 1)),
        lateral_acceleration_mps2=sign * 16.0, lateral_acceleration_confidence_mps2=10.0 if top else 0.0,
        vertical_acceleration_mps2=sign * 16.0, vertical_acceleration_confidence_mps2=10.0 if top else 0.0,
        performance_class=7 if top else 0)
    names = [field.name for field in its_pb2.AccelerationControl.DESCRIPTOR.fields]
    hf.acceleration_control.CopyFrom(its_pb2.AccelerationControl(**{name: top for name in names}))
    hf.cen_dsrc_tolling_zone.CopyFrom(its_pb2.CenDsrcTollingZone(latitude_deg=sign * 90.0, longitude_deg=sign * 180.0))
    if top:
        hf.cen_dsrc_tolling_zone.zone_id = 134_217_727
    lights = [field.name for field in its_pb2.ExteriorLights.DESCRIPTOR.fields]
    low = its_pb2.CamBasicVehicleLowFrequency(
        vehicle_role=its_pb2.VEHICLE_ROLE_RESERVED3 if top else its_pb2.VEHICLE_ROLE_DEFAULT,
        exterior_lights=its_pb2.ExteriorLights(**{name: top for name in lights}),
        path_history=[path_point(top) for _ in range(40 if top else 0)])
    return its_pb2.CamContent(
        protocol_version=protocol_version, station_id=MAX_STATION_ID if top else 0,
        generation_delta_time_ms=65_535 if top else 0, station_type=255 if top else 0,
        reference_position=position(top), high_frequency=hf, low_frequency=low)


def denm(top: bool, protocol_version: int = 1) -> its_pb2.DenmContent:
    content = its_pb2.DenmContent(
        protocol_version=protocol_version, station_id=MAX_STATION_ID if top else 0,
        originating_station_id=MAX_STATION_ID if top else 0, sequence_number=65_535 if top else 0,
        detection_time_tai_ms=MAX_TIMESTAMP_ITS_MS if top else 0, reference_time_tai_ms=MAX_TIMESTAMP_ITS_MS if top else 0,
        termination=its_pb2.DENM_TERMINATION_NEGATION if top else its_pb2.DENM_TERMINATION_CANCELLATION,
        event_position=position(top),
        relevance_distance=its_pb2.RELEVANCE_DISTANCE_OVER_10KM if top else its_pb2.RELEVANCE_DISTANCE_LESS_THAN_50M,
        relevance_traffic_direction=its_pb2.RELEVANCE_TRAFFIC_DIRECTION_OPPOSITE if top
        else its_pb2.RELEVANCE_TRAFFIC_DIRECTION_ALL,
        validity_duration_s=86_400.0 if top else 0.0, transmission_interval_s=10.0 if top else 0.001,
        station_type=255 if top else 0)
    cause = its_pb2.CauseCode(cause_code=255, sub_cause_code=255) if top else its_pb2.CauseCode()
    content.situation.CopyFrom(its_pb2.DenmSituation(
        information_quality=7 if top else 0, event_type=cause,
        event_history=[its_pb2.EventPoint(position=path_point(True), information_quality=7)] * (23 if top else 0)))
    if top:
        content.situation.linked_cause.CopyFrom(cause)
    content.location.CopyFrom(its_pb2.DenmLocation(
        traces=[its_pb2.PathHistory(points=[path_point(top)] * (40 if top else 0))] * (7 if top else 1),
        road_type=its_pb2.ROAD_TYPE_NON_URBAN_WITH_SEPARATION if top else its_pb2.ROAD_TYPE_URBAN_NO_SEPARATION))
    if top:
        content.location.event_speed_mps = 163.82
        content.location.event_speed_confidence_mps = 1.25
        content.location.event_position_heading_rad = ETSI_MAX_HEADING_AS_ENU_RAD
        content.location.event_position_heading_confidence_rad = math.radians(12.5)
    road_works = its_pb2.DenmRoadWorks(
        light_bar_activated=top, siren_activated=top, speed_limit_mps=255 / 3.6 if top else 1 / 3.6,
        closed_lanes=its_pb2.ClosedLanes(
            hard_shoulder_status=its_pb2.HARD_SHOULDER_STATUS_AVAILABLE_FOR_DRIVING if top
            else its_pb2.HARD_SHOULDER_STATUS_AVAILABLE_FOR_STOPPING,
            driving_lane_closed=[top] * ((14 if protocol_version == 1 else 13) if top else 1)))
    content.alacarte.CopyFrom(its_pb2.DenmAlacarte(
        lane_position=14 if top else -1, external_temperature_c=67.0 if top else -60.0, road_works=road_works,
        positioning_solution=5 if top else 0))
    return content


def iclcm(top: bool) -> its_pb2.IclcmContent:
    content = its_pb2.IclcmContent(
        protocol_version=1, station_id=MAX_STATION_ID if top else 0, generation_delta_time_ms=65_535 if top else 0,
        rear_axle_location_m=40.95 if top else 0.0,
        controller_type=its_pb2.CONTROLLER_TYPE_CACC if top else its_pb2.CONTROLLER_TYPE_MANUAL,
        response_time_constant_s=10.0 if top else 0.0, response_time_delay_s=10.0 if top else 0.0,
        target_longitudinal_acceleration_mps2=10.0 if top else -10.0, time_headway_s=36.0 if top else 0.0,
        cruise_speed_mps=50.0 if top else 0.0, has_low_frequency=True, end_of_scenario=top,
        mio_id=MAX_STATION_ID if top else 0, mio_range_m=655.34 if top else 0.0,
        mio_bearing_rad=3.142 if top else -3.142, mio_range_rate_mps=327.66 if top else -327.67,
        lane=3 if top else 1, forward_id=MAX_STATION_ID if top else 0, backward_id=MAX_STATION_ID if top else 0,
        acknowledge_flag=top, merge_request=top, merge_safe_to_merge=top, merge_flag=top, merge_flag_tail=top,
        merge_flag_head=top, platoon_id=255 if top else 0, distance_travelled_cz_m=1000.0 if top else 0.0,
        intention=its_pb2.INTENTION_TURN_RIGHT if top else its_pb2.INTENTION_STRAIGHT,
        counter_intersection=3 if top else 0)
    if top:
        content.participants_ready = True
        content.start_platoon = its_pb2.START_PLATOON_B_AT_60_KPH
    return content
