from coopdrive.v1 import header_pb2 as _header_pb2
from coopdrive.v1 import gnss_pb2 as _gnss_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class LocalisationMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LOCALISATION_MODE_UNSPECIFIED: _ClassVar[LocalisationMode]
    LOCALISATION_MODE_GNSS_PRECISE: _ClassVar[LocalisationMode]
    LOCALISATION_MODE_GNSS_DEGRADED: _ClassVar[LocalisationMode]
    LOCALISATION_MODE_DEAD_RECKONING: _ClassVar[LocalisationMode]
    LOCALISATION_MODE_LOST: _ClassVar[LocalisationMode]
LOCALISATION_MODE_UNSPECIFIED: LocalisationMode
LOCALISATION_MODE_GNSS_PRECISE: LocalisationMode
LOCALISATION_MODE_GNSS_DEGRADED: LocalisationMode
LOCALISATION_MODE_DEAD_RECKONING: LocalisationMode
LOCALISATION_MODE_LOST: LocalisationMode

class LanePosition(_message.Message):
    __slots__ = ("matched", "lane_index", "lane_id", "road_id", "station_m", "lateral_offset_m", "heading_error_rad", "lane_width_m", "curvature_1pm")
    MATCHED_FIELD_NUMBER: _ClassVar[int]
    LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    LANE_ID_FIELD_NUMBER: _ClassVar[int]
    ROAD_ID_FIELD_NUMBER: _ClassVar[int]
    STATION_M_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    HEADING_ERROR_RAD_FIELD_NUMBER: _ClassVar[int]
    LANE_WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_1PM_FIELD_NUMBER: _ClassVar[int]
    matched: bool
    lane_index: int
    lane_id: str
    road_id: str
    station_m: float
    lateral_offset_m: float
    heading_error_rad: float
    lane_width_m: float
    curvature_1pm: float
    def __init__(self, matched: _Optional[bool] = ..., lane_index: _Optional[int] = ..., lane_id: _Optional[str] = ..., road_id: _Optional[str] = ..., station_m: _Optional[float] = ..., lateral_offset_m: _Optional[float] = ..., heading_error_rad: _Optional[float] = ..., lane_width_m: _Optional[float] = ..., curvature_1pm: _Optional[float] = ...) -> None: ...

class EgoState(_message.Message):
    __slots__ = ("header", "x_m", "y_m", "heading_rad", "speed_mps", "accel_mps2", "yaw_rate_radps", "covariance", "mode", "position_std_m", "last_fix_mode", "latitude_deg", "longitude_deg", "lane")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    HEADING_RAD_FIELD_NUMBER: _ClassVar[int]
    SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    ACCEL_MPS2_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_RADPS_FIELD_NUMBER: _ClassVar[int]
    COVARIANCE_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    POSITION_STD_M_FIELD_NUMBER: _ClassVar[int]
    LAST_FIX_MODE_FIELD_NUMBER: _ClassVar[int]
    LATITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    LONGITUDE_DEG_FIELD_NUMBER: _ClassVar[int]
    LANE_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    x_m: float
    y_m: float
    heading_rad: float
    speed_mps: float
    accel_mps2: float
    yaw_rate_radps: float
    covariance: _containers.RepeatedScalarFieldContainer[float]
    mode: LocalisationMode
    position_std_m: float
    last_fix_mode: _gnss_pb2.FixMode
    latitude_deg: float
    longitude_deg: float
    lane: LanePosition
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., x_m: _Optional[float] = ..., y_m: _Optional[float] = ..., heading_rad: _Optional[float] = ..., speed_mps: _Optional[float] = ..., accel_mps2: _Optional[float] = ..., yaw_rate_radps: _Optional[float] = ..., covariance: _Optional[_Iterable[float]] = ..., mode: _Optional[_Union[LocalisationMode, str]] = ..., position_std_m: _Optional[float] = ..., last_fix_mode: _Optional[_Union[_gnss_pb2.FixMode, str]] = ..., latitude_deg: _Optional[float] = ..., longitude_deg: _Optional[float] = ..., lane: _Optional[_Union[LanePosition, _Mapping]] = ...) -> None: ...
