from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class ItsMessageType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ITS_MESSAGE_TYPE_UNSPECIFIED: _ClassVar[ItsMessageType]
    ITS_MESSAGE_TYPE_DENM: _ClassVar[ItsMessageType]
    ITS_MESSAGE_TYPE_CAM: _ClassVar[ItsMessageType]
    ITS_MESSAGE_TYPE_ICLCM: _ClassVar[ItsMessageType]

class StationType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    STATION_TYPE_UNKNOWN: _ClassVar[StationType]
    STATION_TYPE_PEDESTRIAN: _ClassVar[StationType]
    STATION_TYPE_CYCLIST: _ClassVar[StationType]
    STATION_TYPE_MOPED: _ClassVar[StationType]
    STATION_TYPE_MOTORCYCLE: _ClassVar[StationType]
    STATION_TYPE_PASSENGER_CAR: _ClassVar[StationType]
    STATION_TYPE_BUS: _ClassVar[StationType]
    STATION_TYPE_LIGHT_TRUCK: _ClassVar[StationType]
    STATION_TYPE_HEAVY_TRUCK: _ClassVar[StationType]
    STATION_TYPE_TRAILER: _ClassVar[StationType]
    STATION_TYPE_SPECIAL_VEHICLES: _ClassVar[StationType]
    STATION_TYPE_TRAM: _ClassVar[StationType]
    STATION_TYPE_ROAD_SIDE_UNIT: _ClassVar[StationType]

class DriveDirection(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    DRIVE_DIRECTION_UNAVAILABLE: _ClassVar[DriveDirection]
    DRIVE_DIRECTION_FORWARD: _ClassVar[DriveDirection]
    DRIVE_DIRECTION_BACKWARD: _ClassVar[DriveDirection]

class CurvatureCalculationMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    CURVATURE_CALCULATION_MODE_UNAVAILABLE: _ClassVar[CurvatureCalculationMode]
    CURVATURE_CALCULATION_MODE_YAW_RATE_USED: _ClassVar[CurvatureCalculationMode]
    CURVATURE_CALCULATION_MODE_YAW_RATE_NOT_USED: _ClassVar[CurvatureCalculationMode]

class VehicleLengthConfidence(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    VEHICLE_LENGTH_CONFIDENCE_UNAVAILABLE: _ClassVar[VehicleLengthConfidence]
    VEHICLE_LENGTH_CONFIDENCE_NO_TRAILER_PRESENT: _ClassVar[VehicleLengthConfidence]
    VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_KNOWN_LENGTH: _ClassVar[VehicleLengthConfidence]
    VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_UNKNOWN_LENGTH: _ClassVar[VehicleLengthConfidence]
    VEHICLE_LENGTH_CONFIDENCE_TRAILER_PRESENCE_UNKNOWN: _ClassVar[VehicleLengthConfidence]

class VehicleRole(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    VEHICLE_ROLE_DEFAULT: _ClassVar[VehicleRole]
    VEHICLE_ROLE_PUBLIC_TRANSPORT: _ClassVar[VehicleRole]
    VEHICLE_ROLE_SPECIAL_TRANSPORT: _ClassVar[VehicleRole]
    VEHICLE_ROLE_DANGEROUS_GOODS: _ClassVar[VehicleRole]
    VEHICLE_ROLE_ROAD_WORK: _ClassVar[VehicleRole]
    VEHICLE_ROLE_RESCUE: _ClassVar[VehicleRole]
    VEHICLE_ROLE_EMERGENCY: _ClassVar[VehicleRole]
    VEHICLE_ROLE_SAFETY_CAR: _ClassVar[VehicleRole]
    VEHICLE_ROLE_AGRICULTURE: _ClassVar[VehicleRole]
    VEHICLE_ROLE_COMMERCIAL: _ClassVar[VehicleRole]
    VEHICLE_ROLE_MILITARY: _ClassVar[VehicleRole]
    VEHICLE_ROLE_ROAD_OPERATOR: _ClassVar[VehicleRole]
    VEHICLE_ROLE_TAXI: _ClassVar[VehicleRole]
    VEHICLE_ROLE_RESERVED1: _ClassVar[VehicleRole]
    VEHICLE_ROLE_RESERVED2: _ClassVar[VehicleRole]
    VEHICLE_ROLE_RESERVED3: _ClassVar[VehicleRole]

class DenmTermination(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    DENM_TERMINATION_NONE: _ClassVar[DenmTermination]
    DENM_TERMINATION_CANCELLATION: _ClassVar[DenmTermination]
    DENM_TERMINATION_NEGATION: _ClassVar[DenmTermination]

class RelevanceDistance(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    RELEVANCE_DISTANCE_UNSPECIFIED: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_50M: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_100M: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_200M: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_500M: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_1000M: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_5KM: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_LESS_THAN_10KM: _ClassVar[RelevanceDistance]
    RELEVANCE_DISTANCE_OVER_10KM: _ClassVar[RelevanceDistance]

class RelevanceTrafficDirection(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    RELEVANCE_TRAFFIC_DIRECTION_UNSPECIFIED: _ClassVar[RelevanceTrafficDirection]
    RELEVANCE_TRAFFIC_DIRECTION_ALL: _ClassVar[RelevanceTrafficDirection]
    RELEVANCE_TRAFFIC_DIRECTION_UPSTREAM: _ClassVar[RelevanceTrafficDirection]
    RELEVANCE_TRAFFIC_DIRECTION_DOWNSTREAM: _ClassVar[RelevanceTrafficDirection]
    RELEVANCE_TRAFFIC_DIRECTION_OPPOSITE: _ClassVar[RelevanceTrafficDirection]

class RoadType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ROAD_TYPE_UNSPECIFIED: _ClassVar[RoadType]
    ROAD_TYPE_URBAN_NO_SEPARATION: _ClassVar[RoadType]
    ROAD_TYPE_URBAN_WITH_SEPARATION: _ClassVar[RoadType]
    ROAD_TYPE_NON_URBAN_NO_SEPARATION: _ClassVar[RoadType]
    ROAD_TYPE_NON_URBAN_WITH_SEPARATION: _ClassVar[RoadType]

class HardShoulderStatus(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    HARD_SHOULDER_STATUS_UNSPECIFIED: _ClassVar[HardShoulderStatus]
    HARD_SHOULDER_STATUS_AVAILABLE_FOR_STOPPING: _ClassVar[HardShoulderStatus]
    HARD_SHOULDER_STATUS_CLOSED: _ClassVar[HardShoulderStatus]
    HARD_SHOULDER_STATUS_AVAILABLE_FOR_DRIVING: _ClassVar[HardShoulderStatus]

class ControllerType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    CONTROLLER_TYPE_MANUAL: _ClassVar[ControllerType]
    CONTROLLER_TYPE_CC: _ClassVar[ControllerType]
    CONTROLLER_TYPE_ACC: _ClassVar[ControllerType]
    CONTROLLER_TYPE_CACC: _ClassVar[ControllerType]

class StartPlatoon(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    START_PLATOON_A_AT_80_KPH: _ClassVar[StartPlatoon]
    START_PLATOON_B_AT_60_KPH: _ClassVar[StartPlatoon]

class Intention(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    INTENTION_UNSPECIFIED: _ClassVar[Intention]
    INTENTION_STRAIGHT: _ClassVar[Intention]
    INTENTION_TURN_LEFT: _ClassVar[Intention]
    INTENTION_TURN_RIGHT: _ClassVar[Intention]
ITS_MESSAGE_TYPE_UNSPECIFIED: ItsMessageType
ITS_MESSAGE_TYPE_DENM: ItsMessageType
ITS_MESSAGE_TYPE_CAM: ItsMessageType
ITS_MESSAGE_TYPE_ICLCM: ItsMessageType
STATION_TYPE_UNKNOWN: StationType
STATION_TYPE_PEDESTRIAN: StationType
STATION_TYPE_CYCLIST: StationType
STATION_TYPE_MOPED: StationType
STATION_TYPE_MOTORCYCLE: StationType
STATION_TYPE_PASSENGER_CAR: StationType
STATION_TYPE_BUS: StationType
STATION_TYPE_LIGHT_TRUCK: StationType
STATION_TYPE_HEAVY_TRUCK: StationType
STATION_TYPE_TRAILER: StationType
STATION_TYPE_SPECIAL_VEHICLES: StationType
STATION_TYPE_TRAM: StationType
STATION_TYPE_ROAD_SIDE_UNIT: StationType
DRIVE_DIRECTION_UNAVAILABLE: DriveDirection
DRIVE_DIRECTION_FORWARD: DriveDirection
DRIVE_DIRECTION_BACKWARD: DriveDirection
CURVATURE_CALCULATION_MODE_UNAVAILABLE: CurvatureCalculationMode
CURVATURE_CALCULATION_MODE_YAW_RATE_USED: CurvatureCalculationMode
CURVATURE_CALCULATION_MODE_YAW_RATE_NOT_USED: CurvatureCalculationMode
VEHICLE_LENGTH_CONFIDENCE_UNAVAILABLE: VehicleLengthConfidence
VEHICLE_LENGTH_CONFIDENCE_NO_TRAILER_PRESENT: VehicleLengthConfidence
VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_KNOWN_LENGTH: VehicleLengthConfidence
VEHICLE_LENGTH_CONFIDENCE_TRAILER_WITH_UNKNOWN_LENGTH: VehicleLengthConfidence
VEHICLE_LENGTH_CONFIDENCE_TRAILER_PRESENCE_UNKNOWN: VehicleLengthConfidence
VEHICLE_ROLE_DEFAULT: VehicleRole
VEHICLE_ROLE_PUBLIC_TRANSPORT: VehicleRole
VEHICLE_ROLE_SPECIAL_TRANSPORT: VehicleRole
VEHICLE_ROLE_DANGEROUS_GOODS: VehicleRole
VEHICLE_ROLE_ROAD_WORK: VehicleRole
VEHICLE_ROLE_RESCUE: VehicleRole
VEHICLE_ROLE_EMERGENCY: VehicleRole
VEHICLE_ROLE_SAFETY_CAR: VehicleRole
VEHICLE_ROLE_AGRICULTURE: VehicleRole
VEHICLE_ROLE_COMMERCIAL: VehicleRole
VEHICLE_ROLE_MILITARY: VehicleRole
VEHICLE_ROLE_ROAD_OPERATOR: VehicleRole
VEHICLE_ROLE_TAXI: VehicleRole
VEHICLE_ROLE_RESERVED1: VehicleRole
VEHICLE_ROLE_RESERVED2: VehicleRole
VEHICLE_ROLE_RESERVED3: VehicleRole
DENM_TERMINATION_NONE: DenmTermination
DENM_TERMINATION_CANCELLATION: DenmTermination
DENM_TERMINATION_NEGATION: DenmTermination
RELEVANCE_DISTANCE_UNSPECIFIED: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_50M: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_100M: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_200M: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_500M: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_1000M: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_5KM: RelevanceDistance
RELEVANCE_DISTANCE_LESS_THAN_10KM: RelevanceDistance
RELEVANCE_DISTANCE_OVER_10KM: RelevanceDistance
RELEVANCE_TRAFFIC_DIRECTION_UNSPECIFIED: RelevanceTrafficDirection
RELEVANCE_TRAFFIC_DIRECTION_ALL: RelevanceTrafficDirection
RELEVANCE_TRAFFIC_DIRECTION_UPSTREAM: RelevanceTrafficDirection
RELEVANCE_TRAFFIC_DIRECTION_DOWNSTREAM: RelevanceTrafficDirection
RELEVANCE_TRAFFIC_DIRECTION_OPPOSITE: RelevanceTrafficDirection
ROAD_TYPE_UNSPECIFIED: RoadType
ROAD_TYPE_URBAN_NO_SEPARATION: RoadType
ROAD_TYPE_URBAN_WITH_SEPARATION: RoadType
ROAD_TYPE_NON_URBAN_NO_SEPARATION: RoadType
ROAD_TYPE_NON_URBAN_WITH_SEPARATION: RoadType
HARD_SHOULDER_STATUS_UNSPECIFIED: HardShoulderStatus
HARD_SHOULDER_STATUS_AVAILABLE_FOR_STOPPING: HardShoulderStatus
HARD_SHOULDER_STATUS_CLOSED: HardShoulderStatus
HARD_SHOULDER_STATUS_AVAILABLE_FOR_DRIVING: HardShoulderStatus
CONTROLLER_TYPE_MANUAL: ControllerType
CONTROLLER_TYPE_CC: ControllerType
CONTROLLER_TYPE_ACC: ControllerType
CONTROLLER_TYPE_CACC: ControllerType
START_PLATOON_A_AT_80_KPH: StartPlatoon
START_PLATOON_B_AT_60_KPH: StartPlatoon
INTENTION_UNSPECIFIED: Intention
INTENTION_STRAIGHT: Intention
INTENTION_TURN_LEFT: Intention
INTENTION_TURN_RIGHT: Intention

class ReferencePosition(_message.Message):
    __slots__ = ("latitude_deg", "longitude_deg", "altitude_m", "semi_major_confidence_m", "semi_minor_confidence_m", "semi_major_orientation_rad", "altitude_confidence_m")
    LATITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    LONGITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    ALTITUDE_M_FIELD_NUMBER: _ClassVar[int]
    SEMI_MAJOR_CONFIDENCE_M_FIELD_NUMBER: _ClassVar[int]
    SEMI_MINOR_CONFIDENCE_M_FIELD_NUMBER: _ClassVar[int]
    SEMI_MAJOR_ORIENTATION_RAD_FIELD_NUMBER: _ClassVar[int]
    ALTITUDE_CONFIDENCE_M_FIELD_NUMBER: _ClassVar[int]
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    semi_major_confidence_m: float
    semi_minor_confidence_m: float
    semi_major_orientation_rad: float
    altitude_confidence_m: float
    def __init__(self, latitude_deg: _Optional[float] = ..., longitude_deg: _Optional[float] = ..., altitude_m: _Optional[float] = ..., semi_major_confidence_m: _Optional[float] = ..., semi_minor_confidence_m: _Optional[float] = ..., semi_major_orientation_rad: _Optional[float] = ..., altitude_confidence_m: _Optional[float] = ...) -> None: ...

class PathPoint(_message.Message):
    __slots__ = ("delta_latitude_deg", "delta_longitude_deg", "delta_altitude_m", "delta_time_s")
    DELTA_LATITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    DELTA_LONGITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    DELTA_ALTITUDE_M_FIELD_NUMBER: _ClassVar[int]
    DELTA_TIME_S_FIELD_NUMBER: _ClassVar[int]
    delta_latitude_deg: float
    delta_longitude_deg: float
    delta_altitude_m: float
    delta_time_s: float
    def __init__(self, delta_latitude_deg: _Optional[float] = ..., delta_longitude_deg: _Optional[float] = ..., delta_altitude_m: _Optional[float] = ..., delta_time_s: _Optional[float] = ...) -> None: ...

class ExteriorLights(_message.Message):
    __slots__ = ("low_beam_headlights_on", "high_beam_headlights_on", "left_turn_signal_on", "right_turn_signal_on", "daytime_running_lights_on", "reverse_light_on", "fog_light_on", "parking_lights_on")
    LOW_BEAM_HEADLIGHTS_ON_FIELD_NUMBER: _ClassVar[int]
    HIGH_BEAM_HEADLIGHTS_ON_FIELD_NUMBER: _ClassVar[int]
    LEFT_TURN_SIGNAL_ON_FIELD_NUMBER: _ClassVar[int]
    RIGHT_TURN_SIGNAL_ON_FIELD_NUMBER: _ClassVar[int]
    DAYTIME_RUNNING_LIGHTS_ON_FIELD_NUMBER: _ClassVar[int]
    REVERSE_LIGHT_ON_FIELD_NUMBER: _ClassVar[int]
    FOG_LIGHT_ON_FIELD_NUMBER: _ClassVar[int]
    PARKING_LIGHTS_ON_FIELD_NUMBER: _ClassVar[int]
    low_beam_headlights_on: bool
    high_beam_headlights_on: bool
    left_turn_signal_on: bool
    right_turn_signal_on: bool
    daytime_running_lights_on: bool
    reverse_light_on: bool
    fog_light_on: bool
    parking_lights_on: bool
    def __init__(self, low_beam_headlights_on: _Optional[bool] = ..., high_beam_headlights_on: _Optional[bool] = ..., left_turn_signal_on: _Optional[bool] = ..., right_turn_signal_on: _Optional[bool] = ..., daytime_running_lights_on: _Optional[bool] = ..., reverse_light_on: _Optional[bool] = ..., fog_light_on: _Optional[bool] = ..., parking_lights_on: _Optional[bool] = ...) -> None: ...

class AccelerationControl(_message.Message):
    __slots__ = ("brake_pedal_engaged", "gas_pedal_engaged", "emergency_brake_engaged", "collision_warning_engaged", "acc_engaged", "cruise_control_engaged", "speed_limiter_engaged")
    BRAKE_PEDAL_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    GAS_PEDAL_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    EMERGENCY_BRAKE_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    COLLISION_WARNING_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    ACC_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    CRUISE_CONTROL_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    SPEED_LIMITER_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    brake_pedal_engaged: bool
    gas_pedal_engaged: bool
    emergency_brake_engaged: bool
    collision_warning_engaged: bool
    acc_engaged: bool
    cruise_control_engaged: bool
    speed_limiter_engaged: bool
    def __init__(self, brake_pedal_engaged: _Optional[bool] = ..., gas_pedal_engaged: _Optional[bool] = ..., emergency_brake_engaged: _Optional[bool] = ..., collision_warning_engaged: _Optional[bool] = ..., acc_engaged: _Optional[bool] = ..., cruise_control_engaged: _Optional[bool] = ..., speed_limiter_engaged: _Optional[bool] = ...) -> None: ...

class CamBasicVehicleHighFrequency(_message.Message):
    __slots__ = ("heading_rad", "heading_confidence_rad", "speed_mps", "speed_confidence_mps", "drive_direction", "vehicle_length_m", "vehicle_length_confidence", "vehicle_width_m", "longitudinal_acceleration_mps2", "longitudinal_acceleration_confidence_mps2", "curvature_per_m", "curvature_confidence_per_m", "curvature_calculation_mode", "yaw_rate_radps", "yaw_rate_confidence_radps", "acceleration_control", "lane_position", "steering_wheel_angle_rad", "steering_wheel_angle_confidence_rad", "lateral_acceleration_mps2", "lateral_acceleration_confidence_mps2", "vertical_acceleration_mps2", "vertical_acceleration_confidence_mps2", "performance_class", "cen_dsrc_tolling_zone")
    HEADING_RAD_FIELD_NUMBER: _ClassVar[int]
    HEADING_CONFIDENCE_RAD_FIELD_NUMBER: _ClassVar[int]
    SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    SPEED_CONFIDENCE_MPS_FIELD_NUMBER: _ClassVar[int]
    DRIVE_DIRECTION_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_LENGTH_M_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_LENGTH_CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    LONGITUDINAL_ACCELERATION_MPS2_FIELD_NUMBER: _ClassVar[int]
    LONGITUDINAL_ACCELERATION_CONFIDENCE_MPS2_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_PER_M_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_CONFIDENCE_PER_M_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_CALCULATION_MODE_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_RADPS_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_CONFIDENCE_RADPS_FIELD_NUMBER: _ClassVar[int]
    ACCELERATION_CONTROL_FIELD_NUMBER: _ClassVar[int]
    LANE_POSITION_FIELD_NUMBER: _ClassVar[int]
    STEERING_WHEEL_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    STEERING_WHEEL_ANGLE_CONFIDENCE_RAD_FIELD_NUMBER: _ClassVar[int]
    LATERAL_ACCELERATION_MPS2_FIELD_NUMBER: _ClassVar[int]
    LATERAL_ACCELERATION_CONFIDENCE_MPS2_FIELD_NUMBER: _ClassVar[int]
    VERTICAL_ACCELERATION_MPS2_FIELD_NUMBER: _ClassVar[int]
    VERTICAL_ACCELERATION_CONFIDENCE_MPS2_FIELD_NUMBER: _ClassVar[int]
    PERFORMANCE_CLASS_FIELD_NUMBER: _ClassVar[int]
    CEN_DSRC_TOLLING_ZONE_FIELD_NUMBER: _ClassVar[int]
    heading_rad: float
    heading_confidence_rad: float
    speed_mps: float
    speed_confidence_mps: float
    drive_direction: DriveDirection
    vehicle_length_m: float
    vehicle_length_confidence: VehicleLengthConfidence
    vehicle_width_m: float
    longitudinal_acceleration_mps2: float
    longitudinal_acceleration_confidence_mps2: float
    curvature_per_m: float
    curvature_confidence_per_m: float
    curvature_calculation_mode: CurvatureCalculationMode
    yaw_rate_radps: float
    yaw_rate_confidence_radps: float
    acceleration_control: AccelerationControl
    lane_position: int
    steering_wheel_angle_rad: float
    steering_wheel_angle_confidence_rad: float
    lateral_acceleration_mps2: float
    lateral_acceleration_confidence_mps2: float
    vertical_acceleration_mps2: float
    vertical_acceleration_confidence_mps2: float
    performance_class: int
    cen_dsrc_tolling_zone: CenDsrcTollingZone
    def __init__(self, heading_rad: _Optional[float] = ..., heading_confidence_rad: _Optional[float] = ..., speed_mps: _Optional[float] = ..., speed_confidence_mps: _Optional[float] = ..., drive_direction: _Optional[_Union[DriveDirection, str]] = ..., vehicle_length_m: _Optional[float] = ..., vehicle_length_confidence: _Optional[_Union[VehicleLengthConfidence, str]] = ..., vehicle_width_m: _Optional[float] = ..., longitudinal_acceleration_mps2: _Optional[float] = ..., longitudinal_acceleration_confidence_mps2: _Optional[float] = ..., curvature_per_m: _Optional[float] = ..., curvature_confidence_per_m: _Optional[float] = ..., curvature_calculation_mode: _Optional[_Union[CurvatureCalculationMode, str]] = ..., yaw_rate_radps: _Optional[float] = ..., yaw_rate_confidence_radps: _Optional[float] = ..., acceleration_control: _Optional[_Union[AccelerationControl, _Mapping]] = ..., lane_position: _Optional[int] = ..., steering_wheel_angle_rad: _Optional[float] = ..., steering_wheel_angle_confidence_rad: _Optional[float] = ..., lateral_acceleration_mps2: _Optional[float] = ..., lateral_acceleration_confidence_mps2: _Optional[float] = ..., vertical_acceleration_mps2: _Optional[float] = ..., vertical_acceleration_confidence_mps2: _Optional[float] = ..., performance_class: _Optional[int] = ..., cen_dsrc_tolling_zone: _Optional[_Union[CenDsrcTollingZone, _Mapping]] = ...) -> None: ...

class CenDsrcTollingZone(_message.Message):
    __slots__ = ("latitude_deg", "longitude_deg", "zone_id")
    LATITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    LONGITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    ZONE_ID_FIELD_NUMBER: _ClassVar[int]
    latitude_deg: float
    longitude_deg: float
    zone_id: int
    def __init__(self, latitude_deg: _Optional[float] = ..., longitude_deg: _Optional[float] = ..., zone_id: _Optional[int] = ...) -> None: ...

class CamBasicVehicleLowFrequency(_message.Message):
    __slots__ = ("vehicle_role", "exterior_lights", "path_history")
    VEHICLE_ROLE_FIELD_NUMBER: _ClassVar[int]
    EXTERIOR_LIGHTS_FIELD_NUMBER: _ClassVar[int]
    PATH_HISTORY_FIELD_NUMBER: _ClassVar[int]
    vehicle_role: VehicleRole
    exterior_lights: ExteriorLights
    path_history: _containers.RepeatedCompositeFieldContainer[PathPoint]
    def __init__(self, vehicle_role: _Optional[_Union[VehicleRole, str]] = ..., exterior_lights: _Optional[_Union[ExteriorLights, _Mapping]] = ..., path_history: _Optional[_Iterable[_Union[PathPoint, _Mapping]]] = ...) -> None: ...

class CamContent(_message.Message):
    __slots__ = ("header", "protocol_version", "station_id", "generation_delta_time_ms", "station_type", "reference_position", "high_frequency", "low_frequency")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PROTOCOL_VERSION_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    GENERATION_DELTA_TIME_MS_FIELD_NUMBER: _ClassVar[int]
    STATION_TYPE_FIELD_NUMBER: _ClassVar[int]
    REFERENCE_POSITION_FIELD_NUMBER: _ClassVar[int]
    HIGH_FREQUENCY_FIELD_NUMBER: _ClassVar[int]
    LOW_FREQUENCY_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    protocol_version: int
    station_id: int
    generation_delta_time_ms: int
    station_type: StationType
    reference_position: ReferencePosition
    high_frequency: CamBasicVehicleHighFrequency
    low_frequency: CamBasicVehicleLowFrequency
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., protocol_version: _Optional[int] = ..., station_id: _Optional[int] = ..., generation_delta_time_ms: _Optional[int] = ..., station_type: _Optional[_Union[StationType, str]] = ..., reference_position: _Optional[_Union[ReferencePosition, _Mapping]] = ..., high_frequency: _Optional[_Union[CamBasicVehicleHighFrequency, _Mapping]] = ..., low_frequency: _Optional[_Union[CamBasicVehicleLowFrequency, _Mapping]] = ...) -> None: ...

class CauseCode(_message.Message):
    __slots__ = ("cause_code", "sub_cause_code")
    CAUSE_CODE_FIELD_NUMBER: _ClassVar[int]
    SUB_CAUSE_CODE_FIELD_NUMBER: _ClassVar[int]
    cause_code: int
    sub_cause_code: int
    def __init__(self, cause_code: _Optional[int] = ..., sub_cause_code: _Optional[int] = ...) -> None: ...

class EventPoint(_message.Message):
    __slots__ = ("position", "information_quality")
    POSITION_FIELD_NUMBER: _ClassVar[int]
    INFORMATION_QUALITY_FIELD_NUMBER: _ClassVar[int]
    position: PathPoint
    information_quality: int
    def __init__(self, position: _Optional[_Union[PathPoint, _Mapping]] = ..., information_quality: _Optional[int] = ...) -> None: ...

class PathHistory(_message.Message):
    __slots__ = ("points",)
    POINTS_FIELD_NUMBER: _ClassVar[int]
    points: _containers.RepeatedCompositeFieldContainer[PathPoint]
    def __init__(self, points: _Optional[_Iterable[_Union[PathPoint, _Mapping]]] = ...) -> None: ...

class DenmSituation(_message.Message):
    __slots__ = ("information_quality", "event_type", "linked_cause", "event_history")
    INFORMATION_QUALITY_FIELD_NUMBER: _ClassVar[int]
    EVENT_TYPE_FIELD_NUMBER: _ClassVar[int]
    LINKED_CAUSE_FIELD_NUMBER: _ClassVar[int]
    EVENT_HISTORY_FIELD_NUMBER: _ClassVar[int]
    information_quality: int
    event_type: CauseCode
    linked_cause: CauseCode
    event_history: _containers.RepeatedCompositeFieldContainer[EventPoint]
    def __init__(self, information_quality: _Optional[int] = ..., event_type: _Optional[_Union[CauseCode, _Mapping]] = ..., linked_cause: _Optional[_Union[CauseCode, _Mapping]] = ..., event_history: _Optional[_Iterable[_Union[EventPoint, _Mapping]]] = ...) -> None: ...

class DenmLocation(_message.Message):
    __slots__ = ("event_speed_mps", "event_speed_confidence_mps", "event_position_heading_rad", "event_position_heading_confidence_rad", "traces", "road_type")
    EVENT_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    EVENT_SPEED_CONFIDENCE_MPS_FIELD_NUMBER: _ClassVar[int]
    EVENT_POSITION_HEADING_RAD_FIELD_NUMBER: _ClassVar[int]
    EVENT_POSITION_HEADING_CONFIDENCE_RAD_FIELD_NUMBER: _ClassVar[int]
    TRACES_FIELD_NUMBER: _ClassVar[int]
    ROAD_TYPE_FIELD_NUMBER: _ClassVar[int]
    event_speed_mps: float
    event_speed_confidence_mps: float
    event_position_heading_rad: float
    event_position_heading_confidence_rad: float
    traces: _containers.RepeatedCompositeFieldContainer[PathHistory]
    road_type: RoadType
    def __init__(self, event_speed_mps: _Optional[float] = ..., event_speed_confidence_mps: _Optional[float] = ..., event_position_heading_rad: _Optional[float] = ..., event_position_heading_confidence_rad: _Optional[float] = ..., traces: _Optional[_Iterable[_Union[PathHistory, _Mapping]]] = ..., road_type: _Optional[_Union[RoadType, str]] = ...) -> None: ...

class ClosedLanes(_message.Message):
    __slots__ = ("hard_shoulder_status", "driving_lane_closed")
    HARD_SHOULDER_STATUS_FIELD_NUMBER: _ClassVar[int]
    DRIVING_LANE_CLOSED_FIELD_NUMBER: _ClassVar[int]
    hard_shoulder_status: HardShoulderStatus
    driving_lane_closed: _containers.RepeatedScalarFieldContainer[bool]
    def __init__(self, hard_shoulder_status: _Optional[_Union[HardShoulderStatus, str]] = ..., driving_lane_closed: _Optional[_Iterable[bool]] = ...) -> None: ...

class DenmRoadWorks(_message.Message):
    __slots__ = ("light_bar_activated", "siren_activated", "closed_lanes", "speed_limit_mps")
    LIGHT_BAR_ACTIVATED_FIELD_NUMBER: _ClassVar[int]
    SIREN_ACTIVATED_FIELD_NUMBER: _ClassVar[int]
    CLOSED_LANES_FIELD_NUMBER: _ClassVar[int]
    SPEED_LIMIT_MPS_FIELD_NUMBER: _ClassVar[int]
    light_bar_activated: bool
    siren_activated: bool
    closed_lanes: ClosedLanes
    speed_limit_mps: float
    def __init__(self, light_bar_activated: _Optional[bool] = ..., siren_activated: _Optional[bool] = ..., closed_lanes: _Optional[_Union[ClosedLanes, _Mapping]] = ..., speed_limit_mps: _Optional[float] = ...) -> None: ...

class DenmAlacarte(_message.Message):
    __slots__ = ("lane_position", "external_temperature_c", "road_works", "positioning_solution")
    LANE_POSITION_FIELD_NUMBER: _ClassVar[int]
    EXTERNAL_TEMPERATURE_C_FIELD_NUMBER: _ClassVar[int]
    ROAD_WORKS_FIELD_NUMBER: _ClassVar[int]
    POSITIONING_SOLUTION_FIELD_NUMBER: _ClassVar[int]
    lane_position: int
    external_temperature_c: float
    road_works: DenmRoadWorks
    positioning_solution: int
    def __init__(self, lane_position: _Optional[int] = ..., external_temperature_c: _Optional[float] = ..., road_works: _Optional[_Union[DenmRoadWorks, _Mapping]] = ..., positioning_solution: _Optional[int] = ...) -> None: ...

class DenmContent(_message.Message):
    __slots__ = ("header", "protocol_version", "station_id", "originating_station_id", "sequence_number", "detection_time_tai_ms", "reference_time_tai_ms", "termination", "event_position", "relevance_distance", "relevance_traffic_direction", "validity_duration_s", "transmission_interval_s", "station_type", "situation", "location", "alacarte")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PROTOCOL_VERSION_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    ORIGINATING_STATION_ID_FIELD_NUMBER: _ClassVar[int]
    SEQUENCE_NUMBER_FIELD_NUMBER: _ClassVar[int]
    DETECTION_TIME_TAI_MS_FIELD_NUMBER: _ClassVar[int]
    REFERENCE_TIME_TAI_MS_FIELD_NUMBER: _ClassVar[int]
    TERMINATION_FIELD_NUMBER: _ClassVar[int]
    EVENT_POSITION_FIELD_NUMBER: _ClassVar[int]
    RELEVANCE_DISTANCE_FIELD_NUMBER: _ClassVar[int]
    RELEVANCE_TRAFFIC_DIRECTION_FIELD_NUMBER: _ClassVar[int]
    VALIDITY_DURATION_S_FIELD_NUMBER: _ClassVar[int]
    TRANSMISSION_INTERVAL_S_FIELD_NUMBER: _ClassVar[int]
    STATION_TYPE_FIELD_NUMBER: _ClassVar[int]
    SITUATION_FIELD_NUMBER: _ClassVar[int]
    LOCATION_FIELD_NUMBER: _ClassVar[int]
    ALACARTE_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    protocol_version: int
    station_id: int
    originating_station_id: int
    sequence_number: int
    detection_time_tai_ms: int
    reference_time_tai_ms: int
    termination: DenmTermination
    event_position: ReferencePosition
    relevance_distance: RelevanceDistance
    relevance_traffic_direction: RelevanceTrafficDirection
    validity_duration_s: float
    transmission_interval_s: float
    station_type: StationType
    situation: DenmSituation
    location: DenmLocation
    alacarte: DenmAlacarte
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., protocol_version: _Optional[int] = ..., station_id: _Optional[int] = ..., originating_station_id: _Optional[int] = ..., sequence_number: _Optional[int] = ..., detection_time_tai_ms: _Optional[int] = ..., reference_time_tai_ms: _Optional[int] = ..., termination: _Optional[_Union[DenmTermination, str]] = ..., event_position: _Optional[_Union[ReferencePosition, _Mapping]] = ..., relevance_distance: _Optional[_Union[RelevanceDistance, str]] = ..., relevance_traffic_direction: _Optional[_Union[RelevanceTrafficDirection, str]] = ..., validity_duration_s: _Optional[float] = ..., transmission_interval_s: _Optional[float] = ..., station_type: _Optional[_Union[StationType, str]] = ..., situation: _Optional[_Union[DenmSituation, _Mapping]] = ..., location: _Optional[_Union[DenmLocation, _Mapping]] = ..., alacarte: _Optional[_Union[DenmAlacarte, _Mapping]] = ...) -> None: ...

class IclcmContent(_message.Message):
    __slots__ = ("header", "protocol_version", "station_id", "generation_delta_time_ms", "rear_axle_location_m", "controller_type", "response_time_constant_s", "response_time_delay_s", "target_longitudinal_acceleration_mps2", "time_headway_s", "cruise_speed_mps", "has_low_frequency", "participants_ready", "start_platoon", "end_of_scenario", "mio_id", "mio_range_m", "mio_bearing_rad", "mio_range_rate_mps", "lane", "forward_id", "backward_id", "acknowledge_flag", "merge_request", "merge_safe_to_merge", "merge_flag", "merge_flag_tail", "merge_flag_head", "platoon_id", "distance_travelled_cz_m", "intention", "counter_intersection")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PROTOCOL_VERSION_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    GENERATION_DELTA_TIME_MS_FIELD_NUMBER: _ClassVar[int]
    REAR_AXLE_LOCATION_M_FIELD_NUMBER: _ClassVar[int]
    CONTROLLER_TYPE_FIELD_NUMBER: _ClassVar[int]
    RESPONSE_TIME_CONSTANT_S_FIELD_NUMBER: _ClassVar[int]
    RESPONSE_TIME_DELAY_S_FIELD_NUMBER: _ClassVar[int]
    TARGET_LONGITUDINAL_ACCELERATION_MPS2_FIELD_NUMBER: _ClassVar[int]
    TIME_HEADWAY_S_FIELD_NUMBER: _ClassVar[int]
    CRUISE_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    HAS_LOW_FREQUENCY_FIELD_NUMBER: _ClassVar[int]
    PARTICIPANTS_READY_FIELD_NUMBER: _ClassVar[int]
    START_PLATOON_FIELD_NUMBER: _ClassVar[int]
    END_OF_SCENARIO_FIELD_NUMBER: _ClassVar[int]
    MIO_ID_FIELD_NUMBER: _ClassVar[int]
    MIO_RANGE_M_FIELD_NUMBER: _ClassVar[int]
    MIO_BEARING_RAD_FIELD_NUMBER: _ClassVar[int]
    MIO_RANGE_RATE_MPS_FIELD_NUMBER: _ClassVar[int]
    LANE_FIELD_NUMBER: _ClassVar[int]
    FORWARD_ID_FIELD_NUMBER: _ClassVar[int]
    BACKWARD_ID_FIELD_NUMBER: _ClassVar[int]
    ACKNOWLEDGE_FLAG_FIELD_NUMBER: _ClassVar[int]
    MERGE_REQUEST_FIELD_NUMBER: _ClassVar[int]
    MERGE_SAFE_TO_MERGE_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_TAIL_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_HEAD_FIELD_NUMBER: _ClassVar[int]
    PLATOON_ID_FIELD_NUMBER: _ClassVar[int]
    DISTANCE_TRAVELLED_CZ_M_FIELD_NUMBER: _ClassVar[int]
    INTENTION_FIELD_NUMBER: _ClassVar[int]
    COUNTER_INTERSECTION_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    protocol_version: int
    station_id: int
    generation_delta_time_ms: int
    rear_axle_location_m: float
    controller_type: ControllerType
    response_time_constant_s: float
    response_time_delay_s: float
    target_longitudinal_acceleration_mps2: float
    time_headway_s: float
    cruise_speed_mps: float
    has_low_frequency: bool
    participants_ready: bool
    start_platoon: StartPlatoon
    end_of_scenario: bool
    mio_id: int
    mio_range_m: float
    mio_bearing_rad: float
    mio_range_rate_mps: float
    lane: int
    forward_id: int
    backward_id: int
    acknowledge_flag: bool
    merge_request: bool
    merge_safe_to_merge: bool
    merge_flag: bool
    merge_flag_tail: bool
    merge_flag_head: bool
    platoon_id: int
    distance_travelled_cz_m: float
    intention: Intention
    counter_intersection: int
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., protocol_version: _Optional[int] = ..., station_id: _Optional[int] = ..., generation_delta_time_ms: _Optional[int] = ..., rear_axle_location_m: _Optional[float] = ..., controller_type: _Optional[_Union[ControllerType, str]] = ..., response_time_constant_s: _Optional[float] = ..., response_time_delay_s: _Optional[float] = ..., target_longitudinal_acceleration_mps2: _Optional[float] = ..., time_headway_s: _Optional[float] = ..., cruise_speed_mps: _Optional[float] = ..., has_low_frequency: _Optional[bool] = ..., participants_ready: _Optional[bool] = ..., start_platoon: _Optional[_Union[StartPlatoon, str]] = ..., end_of_scenario: _Optional[bool] = ..., mio_id: _Optional[int] = ..., mio_range_m: _Optional[float] = ..., mio_bearing_rad: _Optional[float] = ..., mio_range_rate_mps: _Optional[float] = ..., lane: _Optional[int] = ..., forward_id: _Optional[int] = ..., backward_id: _Optional[int] = ..., acknowledge_flag: _Optional[bool] = ..., merge_request: _Optional[bool] = ..., merge_safe_to_merge: _Optional[bool] = ..., merge_flag: _Optional[bool] = ..., merge_flag_tail: _Optional[bool] = ..., merge_flag_head: _Optional[bool] = ..., platoon_id: _Optional[int] = ..., distance_travelled_cz_m: _Optional[float] = ..., intention: _Optional[_Union[Intention, str]] = ..., counter_intersection: _Optional[int] = ...) -> None: ...
