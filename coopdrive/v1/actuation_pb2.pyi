from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class DrivingMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    DRIVING_MODE_UNSPECIFIED: _ClassVar[DrivingMode]
    DRIVING_MODE_MANUAL: _ClassVar[DrivingMode]
    DRIVING_MODE_COOPERATIVE: _ClassVar[DrivingMode]
    DRIVING_MODE_AUTONOMOUS: _ClassVar[DrivingMode]
    DRIVING_MODE_SAFE_STOP: _ClassVar[DrivingMode]

class OverrideReason(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    OVERRIDE_REASON_UNSPECIFIED: _ClassVar[OverrideReason]
    OVERRIDE_REASON_STEERING: _ClassVar[OverrideReason]
    OVERRIDE_REASON_THROTTLE: _ClassVar[OverrideReason]
    OVERRIDE_REASON_BRAKE: _ClassVar[OverrideReason]
DRIVING_MODE_UNSPECIFIED: DrivingMode
DRIVING_MODE_MANUAL: DrivingMode
DRIVING_MODE_COOPERATIVE: DrivingMode
DRIVING_MODE_AUTONOMOUS: DrivingMode
DRIVING_MODE_SAFE_STOP: DrivingMode
OVERRIDE_REASON_UNSPECIFIED: OverrideReason
OVERRIDE_REASON_STEERING: OverrideReason
OVERRIDE_REASON_THROTTLE: OverrideReason
OVERRIDE_REASON_BRAKE: OverrideReason

class ModeAvailability(_message.Message):
    __slots__ = ("mode", "available", "unmet_condition")
    MODE_FIELD_NUMBER: _ClassVar[int]
    AVAILABLE_FIELD_NUMBER: _ClassVar[int]
    UNMET_CONDITION_FIELD_NUMBER: _ClassVar[int]
    mode: DrivingMode
    available: bool
    unmet_condition: str
    def __init__(self, mode: _Optional[_Union[DrivingMode, str]] = ..., available: _Optional[bool] = ..., unmet_condition: _Optional[str] = ...) -> None: ...

class ActuationStatus(_message.Message):
    __slots__ = ("header", "mode", "throttle_ratio", "brake_ratio", "steering_angle_rad", "indicator_left", "indicator_right", "hazard_lights", "availability", "last_mode_change_reason", "frames_sent", "frames_rejected")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    THROTTLE_RATIO_FIELD_NUMBER: _ClassVar[int]
    BRAKE_RATIO_FIELD_NUMBER: _ClassVar[int]
    STEERING_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    INDICATOR_LEFT_FIELD_NUMBER: _ClassVar[int]
    INDICATOR_RIGHT_FIELD_NUMBER: _ClassVar[int]
    HAZARD_LIGHTS_FIELD_NUMBER: _ClassVar[int]
    AVAILABILITY_FIELD_NUMBER: _ClassVar[int]
    LAST_MODE_CHANGE_REASON_FIELD_NUMBER: _ClassVar[int]
    FRAMES_SENT_FIELD_NUMBER: _ClassVar[int]
    FRAMES_REJECTED_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    mode: DrivingMode
    throttle_ratio: float
    brake_ratio: float
    steering_angle_rad: float
    indicator_left: bool
    indicator_right: bool
    hazard_lights: bool
    availability: _containers.RepeatedCompositeFieldContainer[ModeAvailability]
    last_mode_change_reason: str
    frames_sent: int
    frames_rejected: int
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., mode: _Optional[_Union[DrivingMode, str]] = ..., throttle_ratio: _Optional[float] = ..., brake_ratio: _Optional[float] = ..., steering_angle_rad: _Optional[float] = ..., indicator_left: _Optional[bool] = ..., indicator_right: _Optional[bool] = ..., hazard_lights: _Optional[bool] = ..., availability: _Optional[_Iterable[_Union[ModeAvailability, _Mapping]]] = ..., last_mode_change_reason: _Optional[str] = ..., frames_sent: _Optional[int] = ..., frames_rejected: _Optional[int] = ...) -> None: ...

class OverrideEvent(_message.Message):
    __slots__ = ("header", "reason", "value")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    VALUE_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    reason: OverrideReason
    value: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., reason: _Optional[_Union[OverrideReason, str]] = ..., value: _Optional[float] = ...) -> None: ...

class ModeRequest(_message.Message):
    __slots__ = ("header", "mode", "requested_by", "reason")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    REQUESTED_BY_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    mode: DrivingMode
    requested_by: str
    reason: str
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., mode: _Optional[_Union[DrivingMode, str]] = ..., requested_by: _Optional[str] = ..., reason: _Optional[str] = ...) -> None: ...

class EmergencyStop(_message.Message):
    __slots__ = ("header", "requested_by", "reason")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    REQUESTED_BY_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    requested_by: str
    reason: str
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., requested_by: _Optional[str] = ..., reason: _Optional[str] = ...) -> None: ...

class ActuatorCommand(_message.Message):
    __slots__ = ("header", "throttle_ratio", "brake_ratio", "steering_angle_rad", "accel_request_mps2", "indicator_left", "indicator_right", "hazard_lights", "automation_active")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    THROTTLE_RATIO_FIELD_NUMBER: _ClassVar[int]
    BRAKE_RATIO_FIELD_NUMBER: _ClassVar[int]
    STEERING_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    ACCEL_REQUEST_MPS2_FIELD_NUMBER: _ClassVar[int]
    INDICATOR_LEFT_FIELD_NUMBER: _ClassVar[int]
    INDICATOR_RIGHT_FIELD_NUMBER: _ClassVar[int]
    HAZARD_LIGHTS_FIELD_NUMBER: _ClassVar[int]
    AUTOMATION_ACTIVE_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    throttle_ratio: float
    brake_ratio: float
    steering_angle_rad: float
    accel_request_mps2: float
    indicator_left: bool
    indicator_right: bool
    hazard_lights: bool
    automation_active: bool
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., throttle_ratio: _Optional[float] = ..., brake_ratio: _Optional[float] = ..., steering_angle_rad: _Optional[float] = ..., accel_request_mps2: _Optional[float] = ..., indicator_left: _Optional[bool] = ..., indicator_right: _Optional[bool] = ..., hazard_lights: _Optional[bool] = ..., automation_active: _Optional[bool] = ...) -> None: ...
