from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class Gear(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    GEAR_UNSPECIFIED: _ClassVar[Gear]
    GEAR_PARK: _ClassVar[Gear]
    GEAR_REVERSE: _ClassVar[Gear]
    GEAR_NEUTRAL: _ClassVar[Gear]
    GEAR_DRIVE: _ClassVar[Gear]
GEAR_UNSPECIFIED: Gear
GEAR_PARK: Gear
GEAR_REVERSE: Gear
GEAR_NEUTRAL: Gear
GEAR_DRIVE: Gear

class VehicleCanState(_message.Message):
    __slots__ = ("header", "wheel_speed_front_left_mps", "wheel_speed_front_right_mps", "wheel_speed_rear_left_mps", "wheel_speed_rear_right_mps", "yaw_rate_radps", "steering_angle_rad", "throttle_pedal_ratio", "brake_pedal_ratio", "brake_pressure_bar", "gear", "vehicle_speed_mps", "steering_wheel_angle_rad", "turn_signal_left", "turn_signal_right")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    WHEEL_SPEED_FRONT_LEFT_MPS_FIELD_NUMBER: _ClassVar[int]
    WHEEL_SPEED_FRONT_RIGHT_MPS_FIELD_NUMBER: _ClassVar[int]
    WHEEL_SPEED_REAR_LEFT_MPS_FIELD_NUMBER: _ClassVar[int]
    WHEEL_SPEED_REAR_RIGHT_MPS_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_RADPS_FIELD_NUMBER: _ClassVar[int]
    STEERING_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    THROTTLE_PEDAL_RATIO_FIELD_NUMBER: _ClassVar[int]
    BRAKE_PEDAL_RATIO_FIELD_NUMBER: _ClassVar[int]
    BRAKE_PRESSURE_BAR_FIELD_NUMBER: _ClassVar[int]
    GEAR_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    STEERING_WHEEL_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    TURN_SIGNAL_LEFT_FIELD_NUMBER: _ClassVar[int]
    TURN_SIGNAL_RIGHT_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    wheel_speed_front_left_mps: float
    wheel_speed_front_right_mps: float
    wheel_speed_rear_left_mps: float
    wheel_speed_rear_right_mps: float
    yaw_rate_radps: float
    steering_angle_rad: float
    throttle_pedal_ratio: float
    brake_pedal_ratio: float
    brake_pressure_bar: float
    gear: Gear
    vehicle_speed_mps: float
    steering_wheel_angle_rad: float
    turn_signal_left: bool
    turn_signal_right: bool
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., wheel_speed_front_left_mps: _Optional[float] = ..., wheel_speed_front_right_mps: _Optional[float] = ..., wheel_speed_rear_left_mps: _Optional[float] = ..., wheel_speed_rear_right_mps: _Optional[float] = ..., yaw_rate_radps: _Optional[float] = ..., steering_angle_rad: _Optional[float] = ..., throttle_pedal_ratio: _Optional[float] = ..., brake_pedal_ratio: _Optional[float] = ..., brake_pressure_bar: _Optional[float] = ..., gear: _Optional[_Union[Gear, str]] = ..., vehicle_speed_mps: _Optional[float] = ..., steering_wheel_angle_rad: _Optional[float] = ..., turn_signal_left: _Optional[bool] = ..., turn_signal_right: _Optional[bool] = ...) -> None: ...

class ImuSample(_message.Message):
    __slots__ = ("header", "accel_longitudinal_mps2", "accel_lateral_mps2", "yaw_rate_radps")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    ACCEL_LONGITUDINAL_MPS2_FIELD_NUMBER: _ClassVar[int]
    ACCEL_LATERAL_MPS2_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_RADPS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    accel_longitudinal_mps2: float
    accel_lateral_mps2: float
    yaw_rate_radps: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., accel_longitudinal_mps2: _Optional[float] = ..., accel_lateral_mps2: _Optional[float] = ..., yaw_rate_radps: _Optional[float] = ...) -> None: ...

class CanFrame(_message.Message):
    __slots__ = ("header", "channel", "arbitration_id", "is_extended_id", "data", "timestamp_s", "is_error_frame", "is_remote_frame")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    CHANNEL_FIELD_NUMBER: _ClassVar[int]
    ARBITRATION_ID_FIELD_NUMBER: _ClassVar[int]
    IS_EXTENDED_ID_FIELD_NUMBER: _ClassVar[int]
    DATA_FIELD_NUMBER: _ClassVar[int]
    TIMESTAMP_S_FIELD_NUMBER: _ClassVar[int]
    IS_ERROR_FRAME_FIELD_NUMBER: _ClassVar[int]
    IS_REMOTE_FRAME_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    channel: str
    arbitration_id: int
    is_extended_id: bool
    data: bytes
    timestamp_s: float
    is_error_frame: bool
    is_remote_frame: bool
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., channel: _Optional[str] = ..., arbitration_id: _Optional[int] = ..., is_extended_id: _Optional[bool] = ..., data: _Optional[bytes] = ..., timestamp_s: _Optional[float] = ..., is_error_frame: _Optional[bool] = ..., is_remote_frame: _Optional[bool] = ...) -> None: ...

class CanFrames(_message.Message):
    __slots__ = ("header", "frames")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    FRAMES_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    frames: _containers.RepeatedCompositeFieldContainer[CanFrame]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., frames: _Optional[_Iterable[_Union[CanFrame, _Mapping]]] = ...) -> None: ...
