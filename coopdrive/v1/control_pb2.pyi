from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class LongitudinalMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LONGITUDINAL_MODE_UNSPECIFIED: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_CRUISE: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_ACC: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_CACC: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_DCACC: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_EMERGENCY_BRAKE: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_STANDSTILL: _ClassVar[LongitudinalMode]
    LONGITUDINAL_MODE_STOP_LINE: _ClassVar[LongitudinalMode]

class LateralMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LATERAL_MODE_UNSPECIFIED: _ClassVar[LateralMode]
    LATERAL_MODE_OFF: _ClassVar[LateralMode]
    LATERAL_MODE_LANE_KEEPING: _ClassVar[LateralMode]
    LATERAL_MODE_LANE_CHANGE: _ClassVar[LateralMode]
LONGITUDINAL_MODE_UNSPECIFIED: LongitudinalMode
LONGITUDINAL_MODE_CRUISE: LongitudinalMode
LONGITUDINAL_MODE_ACC: LongitudinalMode
LONGITUDINAL_MODE_CACC: LongitudinalMode
LONGITUDINAL_MODE_DCACC: LongitudinalMode
LONGITUDINAL_MODE_EMERGENCY_BRAKE: LongitudinalMode
LONGITUDINAL_MODE_STANDSTILL: LongitudinalMode
LONGITUDINAL_MODE_STOP_LINE: LongitudinalMode
LATERAL_MODE_UNSPECIFIED: LateralMode
LATERAL_MODE_OFF: LateralMode
LATERAL_MODE_LANE_KEEPING: LateralMode
LATERAL_MODE_LANE_CHANGE: LateralMode

class ControlCommand(_message.Message):
    __slots__ = ("header", "accel_request_mps2", "steering_angle_request_rad", "curvature_request_1pm", "longitudinal_mode", "lateral_mode", "emergency_brake", "target_object_id", "gap_m", "desired_gap_m", "time_gap_s", "lateral_error_m", "heading_error_rad", "response_time_constant_s", "response_time_delay_s", "cruise_speed_mps")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    ACCEL_REQUEST_MPS2_FIELD_NUMBER: _ClassVar[int]
    STEERING_ANGLE_REQUEST_RAD_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_REQUEST_1PM_FIELD_NUMBER: _ClassVar[int]
    LONGITUDINAL_MODE_FIELD_NUMBER: _ClassVar[int]
    LATERAL_MODE_FIELD_NUMBER: _ClassVar[int]
    EMERGENCY_BRAKE_FIELD_NUMBER: _ClassVar[int]
    TARGET_OBJECT_ID_FIELD_NUMBER: _ClassVar[int]
    GAP_M_FIELD_NUMBER: _ClassVar[int]
    DESIRED_GAP_M_FIELD_NUMBER: _ClassVar[int]
    TIME_GAP_S_FIELD_NUMBER: _ClassVar[int]
    LATERAL_ERROR_M_FIELD_NUMBER: _ClassVar[int]
    HEADING_ERROR_RAD_FIELD_NUMBER: _ClassVar[int]
    RESPONSE_TIME_CONSTANT_S_FIELD_NUMBER: _ClassVar[int]
    RESPONSE_TIME_DELAY_S_FIELD_NUMBER: _ClassVar[int]
    CRUISE_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    accel_request_mps2: float
    steering_angle_request_rad: float
    curvature_request_1pm: float
    longitudinal_mode: LongitudinalMode
    lateral_mode: LateralMode
    emergency_brake: bool
    target_object_id: int
    gap_m: float
    desired_gap_m: float
    time_gap_s: float
    lateral_error_m: float
    heading_error_rad: float
    response_time_constant_s: float
    response_time_delay_s: float
    cruise_speed_mps: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., accel_request_mps2: _Optional[float] = ..., steering_angle_request_rad: _Optional[float] = ..., curvature_request_1pm: _Optional[float] = ..., longitudinal_mode: _Optional[_Union[LongitudinalMode, str]] = ..., lateral_mode: _Optional[_Union[LateralMode, str]] = ..., emergency_brake: _Optional[bool] = ..., target_object_id: _Optional[int] = ..., gap_m: _Optional[float] = ..., desired_gap_m: _Optional[float] = ..., time_gap_s: _Optional[float] = ..., lateral_error_m: _Optional[float] = ..., heading_error_rad: _Optional[float] = ..., response_time_constant_s: _Optional[float] = ..., response_time_delay_s: _Optional[float] = ..., cruise_speed_mps: _Optional[float] = ...) -> None: ...
