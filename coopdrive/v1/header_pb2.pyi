from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from typing import ClassVar as _ClassVar, Optional as _Optional

DESCRIPTOR: _descriptor.FileDescriptor

class SensorSource(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SENSOR_SOURCE_UNSPECIFIED: _ClassVar[SensorSource]
    SENSOR_SOURCE_LIDAR: _ClassVar[SensorSource]
    SENSOR_SOURCE_RADAR: _ClassVar[SensorSource]
    SENSOR_SOURCE_CAMERA: _ClassVar[SensorSource]
    SENSOR_SOURCE_SONAR: _ClassVar[SensorSource]
    SENSOR_SOURCE_V2V: _ClassVar[SensorSource]
    SENSOR_SOURCE_MAP: _ClassVar[SensorSource]
SENSOR_SOURCE_UNSPECIFIED: SensorSource
SENSOR_SOURCE_LIDAR: SensorSource
SENSOR_SOURCE_RADAR: SensorSource
SENSOR_SOURCE_CAMERA: SensorSource
SENSOR_SOURCE_SONAR: SensorSource
SENSOR_SOURCE_V2V: SensorSource
SENSOR_SOURCE_MAP: SensorSource

class Header(_message.Message):
    __slots__ = ("sample_time_s", "sent_time_s", "vehicle_id", "sender", "sequence")
    SAMPLE_TIME_S_FIELD_NUMBER: _ClassVar[int]
    SENT_TIME_S_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_ID_FIELD_NUMBER: _ClassVar[int]
    SENDER_FIELD_NUMBER: _ClassVar[int]
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    sample_time_s: float
    sent_time_s: float
    vehicle_id: str
    sender: str
    sequence: int
    def __init__(self, sample_time_s: _Optional[float] = ..., sent_time_s: _Optional[float] = ..., vehicle_id: _Optional[str] = ..., sender: _Optional[str] = ..., sequence: _Optional[int] = ...) -> None: ...
