from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class HealthLevel(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    HEALTH_LEVEL_UNSPECIFIED: _ClassVar[HealthLevel]
    HEALTH_LEVEL_OK: _ClassVar[HealthLevel]
    HEALTH_LEVEL_WARN: _ClassVar[HealthLevel]
    HEALTH_LEVEL_ERROR: _ClassVar[HealthLevel]
HEALTH_LEVEL_UNSPECIFIED: HealthLevel
HEALTH_LEVEL_OK: HealthLevel
HEALTH_LEVEL_WARN: HealthLevel
HEALTH_LEVEL_ERROR: HealthLevel

class Diagnostics(_message.Message):
    __slots__ = ("header", "level", "message", "counters")
    class CountersEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: float
        def __init__(self, key: _Optional[str] = ..., value: _Optional[float] = ...) -> None: ...
    HEADER_FIELD_NUMBER: _ClassVar[int]
    LEVEL_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    COUNTERS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    level: HealthLevel
    message: str
    counters: _containers.ScalarMap[str, float]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., level: _Optional[_Union[HealthLevel, str]] = ..., message: _Optional[str] = ..., counters: _Optional[_Mapping[str, float]] = ...) -> None: ...

class ServiceInfo(_message.Message):
    __slots__ = ("service", "vehicle_id", "state", "config_json", "uptime_s", "pid")
    SERVICE_FIELD_NUMBER: _ClassVar[int]
    VEHICLE_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    CONFIG_JSON_FIELD_NUMBER: _ClassVar[int]
    UPTIME_S_FIELD_NUMBER: _ClassVar[int]
    PID_FIELD_NUMBER: _ClassVar[int]
    service: str
    vehicle_id: str
    state: str
    config_json: str
    uptime_s: float
    pid: int
    def __init__(self, service: _Optional[str] = ..., vehicle_id: _Optional[str] = ..., state: _Optional[str] = ..., config_json: _Optional[str] = ..., uptime_s: _Optional[float] = ..., pid: _Optional[int] = ...) -> None: ...
