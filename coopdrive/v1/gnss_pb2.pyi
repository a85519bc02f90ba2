from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class FixMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FIX_MODE_UNSPECIFIED: _ClassVar[FixMode]
    FIX_MODE_NO_FIX: _ClassVar[FixMode]
    FIX_MODE_SINGLE: _ClassVar[FixMode]
    FIX_MODE_SBAS: _ClassVar[FixMode]
    FIX_MODE_DGPS: _ClassVar[FixMode]
    FIX_MODE_RTK_FLOAT: _ClassVar[FixMode]
    FIX_MODE_RTK_FIXED: _ClassVar[FixMode]
FIX_MODE_UNSPECIFIED: FixMode
FIX_MODE_NO_FIX: FixMode
FIX_MODE_SINGLE: FixMode
FIX_MODE_SBAS: FixMode
FIX_MODE_DGPS: FixMode
FIX_MODE_RTK_FLOAT: FixMode
FIX_MODE_RTK_FIXED: FixMode

class GnssFix(_message.Message):
    __slots__ = ("header", "latitude_deg", "longitude_deg", "altitude_m", "fix_mode", "std_east_m", "std_north_m", "std_up_m", "speed_mps", "course_deg", "satellites", "hdop", "utc_time_s", "velocity_valid", "heading_valid", "heading_deg")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    LATITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    LONGITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    ALTITUDE_M_FIELD_NUMBER: _ClassVar[int]
    FIX_MODE_FIELD_NUMBER: _ClassVar[int]
    STD_EAST_M_FIELD_NUMBER: _ClassVar[int]
    STD_NORTH_M_FIELD_NUMBER: _ClassVar[int]
    STD_UP_M_FIELD_NUMBER: _ClassVar[int]
    SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    COURSE_DEG_FIELD_NUMBER: _ClassVar[int]
    SATELLITES_FIELD_NUMBER: _ClassVar[int]
    HDOP_FIELD_NUMBER: _ClassVar[int]
    UTC_TIME_S_FIELD_NUMBER: _ClassVar[int]
    VELOCITY_VALID_FIELD_NUMBER: _ClassVar[int]
    HEADING_VALID_FIELD_NUMBER: _ClassVar[int]
    HEADING_DEG_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    fix_mode: FixMode
    std_east_m: float
    std_north_m: float
    std_up_m: float
    speed_mps: float
    course_deg: float
    satellites: int
    hdop: float
    utc_time_s: float
    velocity_valid: bool
    heading_valid: bool
    heading_deg: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., latitude_deg: _Optional[float] = ..., longitude_deg: _Optional[float] = ..., altitude_m: _Optional[float] = ..., fix_mode: _Optional[_Union[FixMode, str]] = ..., std_east_m: _Optional[float] = ..., std_north_m: _Optional[float] = ..., std_up_m: _Optional[float] = ..., speed_mps: _Optional[float] = ..., course_deg: _Optional[float] = ..., satellites: _Optional[int] = ..., hdop: _Optional[float] = ..., utc_time_s: _Optional[float] = ..., velocity_valid: _Optional[bool] = ..., heading_valid: _Optional[bool] = ..., heading_deg: _Optional[float] = ...) -> None: ...

class NmeaChunk(_message.Message):
    __slots__ = ("header", "data", "port")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    DATA_FIELD_NUMBER: _ClassVar[int]
    PORT_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    data: bytes
    port: str
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., data: _Optional[bytes] = ..., port: _Optional[str] = ...) -> None: ...
