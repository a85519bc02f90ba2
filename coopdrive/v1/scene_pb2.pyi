from coopdrive.v1 import header_pb2 as _header_pb2
from coopdrive.v1 import sensors_pb2 as _sensors_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class LaneSource(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LANE_SOURCE_UNSPECIFIED: _ClassVar[LaneSource]
    LANE_SOURCE_MAP: _ClassVar[LaneSource]
    LANE_SOURCE_CAMERA: _ClassVar[LaneSource]
    LANE_SOURCE_FUSED: _ClassVar[LaneSource]
LANE_SOURCE_UNSPECIFIED: LaneSource
LANE_SOURCE_MAP: LaneSource
LANE_SOURCE_CAMERA: LaneSource
LANE_SOURCE_FUSED: LaneSource

class ScalarProperty(_message.Message):
    __slots__ = ("value", "confidence", "sources", "valid_until_s")
    VALUE_FIELD_NUMBER: _ClassVar[int]
    CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    SOURCES_FIELD_NUMBER: _ClassVar[int]
    VALID_UNTIL_S_FIELD_NUMBER: _ClassVar[int]
    value: float
    confidence: float
    sources: _containers.RepeatedScalarFieldContainer[_header_pb2.SensorSource]
    valid_until_s: float
    def __init__(self, value: _Optional[float] = ..., confidence: _Optional[float] = ..., sources: _Optional[_Iterable[_Union[_header_pb2.SensorSource, str]]] = ..., valid_until_s: _Optional[float] = ...) -> None: ...

class PositionProperty(_message.Message):
    __slots__ = ("x_m", "y_m", "confidence", "sources", "valid_until_s", "std_m")
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    SOURCES_FIELD_NUMBER: _ClassVar[int]
    VALID_UNTIL_S_FIELD_NUMBER: _ClassVar[int]
    STD_M_FIELD_NUMBER: _ClassVar[int]
    x_m: float
    y_m: float
    confidence: float
    sources: _containers.RepeatedScalarFieldContainer[_header_pb2.SensorSource]
    valid_until_s: float
    std_m: float
    def __init__(self, x_m: _Optional[float] = ..., y_m: _Optional[float] = ..., confidence: _Optional[float] = ..., sources: _Optional[_Iterable[_Union[_header_pb2.SensorSource, str]]] = ..., valid_until_s: _Optional[float] = ..., std_m: _Optional[float] = ...) -> None: ...

class IntegerProperty(_message.Message):
    __slots__ = ("value", "confidence", "sources", "valid_until_s")
    VALUE_FIELD_NUMBER: _ClassVar[int]
    CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    SOURCES_FIELD_NUMBER: _ClassVar[int]
    VALID_UNTIL_S_FIELD_NUMBER: _ClassVar[int]
    value: int
    confidence: float
    sources: _containers.RepeatedScalarFieldContainer[_header_pb2.SensorSource]
    valid_until_s: float
    def __init__(self, value: _Optional[int] = ..., confidence: _Optional[float] = ..., sources: _Optional[_Iterable[_Union[_header_pb2.SensorSource, str]]] = ..., valid_until_s: _Optional[float] = ...) -> None: ...

class SceneObject(_message.Message):
    __slots__ = ("object_id", "object_class", "position", "speed_mps", "accel_mps2", "heading_rad", "length_m", "width_m", "lane_index", "station_id", "longitudinal_gap_m", "lateral_offset_m", "relative_speed_mps", "v2v_trust", "ghost", "first_seen_s", "intended_accel_mps2", "v2v_time_s")
    OBJECT_ID_FIELD_NUMBER: _ClassVar[int]
    OBJECT_CLASS_FIELD_NUMBER: _ClassVar[int]
    POSITION_FIELD_NUMBER: _ClassVar[int]
    SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    ACCEL_MPS2_FIELD_NUMBER: _ClassVar[int]
    HEADING_RAD_FIELD_NUMBER: _ClassVar[int]
    LENGTH_M_FIELD_NUMBER: _ClassVar[int]
    WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    LONGITUDINAL_GAP_M_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    RELATIVE_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    V2V_TRUST_FIELD_NUMBER: _ClassVar[int]
    GHOST_FIELD_NUMBER: _ClassVar[int]
    FIRST_SEEN_S_FIELD_NUMBER: _ClassVar[int]
    INTENDED_ACCEL_MPS2_FIELD_NUMBER: _ClassVar[int]
    V2V_TIME_S_FIELD_NUMBER: _ClassVar[int]
    object_id: int
    object_class: _sensors_pb2.ObjectClass
    position: PositionProperty
    speed_mps: ScalarProperty
    accel_mps2: ScalarProperty
    heading_rad: ScalarProperty
    length_m: ScalarProperty
    width_m: ScalarProperty
    lane_index: IntegerProperty
    station_id: IntegerProperty
    longitudinal_gap_m: float
    lateral_offset_m: float
    relative_speed_mps: float
    v2v_trust: float
    ghost: bool
    first_seen_s: float
    intended_accel_mps2: ScalarProperty
    v2v_time_s: float
    def __init__(self, object_id: _Optional[int] = ..., object_class: _Optional[_Union[_sensors_pb2.ObjectClass, str]] = ..., position: _Optional[_Union[PositionProperty, _Mapping]] = ..., speed_mps: _Optional[_Union[ScalarProperty, _Mapping]] = ..., accel_mps2: _Optional[_Union[ScalarProperty, _Mapping]] = ..., heading_rad: _Optional[_Union[ScalarProperty, _Mapping]] = ..., length_m: _Optional[_Union[ScalarProperty, _Mapping]] = ..., width_m: _Optional[_Union[ScalarProperty, _Mapping]] = ..., lane_index: _Optional[_Union[IntegerProperty, _Mapping]] = ..., station_id: _Optional[_Union[IntegerProperty, _Mapping]] = ..., longitudinal_gap_m: _Optional[float] = ..., lateral_offset_m: _Optional[float] = ..., relative_speed_mps: _Optional[float] = ..., v2v_trust: _Optional[float] = ..., ghost: _Optional[bool] = ..., first_seen_s: _Optional[float] = ..., intended_accel_mps2: _Optional[_Union[ScalarProperty, _Mapping]] = ..., v2v_time_s: _Optional[float] = ...) -> None: ...

class LaneNeighbours(_message.Message):
    __slots__ = ("lane_offset", "ahead_object_id", "has_ahead", "behind_object_id", "has_behind")
    LANE_OFFSET_FIELD_NUMBER: _ClassVar[int]
    AHEAD_OBJECT_ID_FIELD_NUMBER: _ClassVar[int]
    HAS_AHEAD_FIELD_NUMBER: _ClassVar[int]
    BEHIND_OBJECT_ID_FIELD_NUMBER: _ClassVar[int]
    HAS_BEHIND_FIELD_NUMBER: _ClassVar[int]
    lane_offset: int
    ahead_object_id: int
    has_ahead: bool
    behind_object_id: int
    has_behind: bool
    def __init__(self, lane_offset: _Optional[int] = ..., ahead_object_id: _Optional[int] = ..., has_ahead: _Optional[bool] = ..., behind_object_id: _Optional[int] = ..., has_behind: _Optional[bool] = ...) -> None: ...

class FreeSpace(_message.Message):
    __slots__ = ("range_m",)
    RANGE_M_FIELD_NUMBER: _ClassVar[int]
    range_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, range_m: _Optional[_Iterable[float]] = ...) -> None: ...

class Scene(_message.Message):
    __slots__ = ("header", "objects", "has_mio", "mio_id", "has_forward_mio", "forward_mio_id", "neighbours", "free_space", "ego_lane_index", "station_trust", "ego_lane")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    OBJECTS_FIELD_NUMBER: _ClassVar[int]
    HAS_MIO_FIELD_NUMBER: _ClassVar[int]
    MIO_ID_FIELD_NUMBER: _ClassVar[int]
    HAS_FORWARD_MIO_FIELD_NUMBER: _ClassVar[int]
    FORWARD_MIO_ID_FIELD_NUMBER: _ClassVar[int]
    NEIGHBOURS_FIELD_NUMBER: _ClassVar[int]
    FREE_SPACE_FIELD_NUMBER: _ClassVar[int]
    EGO_LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    STATION_TRUST_FIELD_NUMBER: _ClassVar[int]
    EGO_LANE_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    objects: _containers.RepeatedCompositeFieldContainer[SceneObject]
    has_mio: bool
    mio_id: int
    has_forward_mio: bool
    forward_mio_id: int
    neighbours: _containers.RepeatedCompositeFieldContainer[LaneNeighbours]
    free_space: FreeSpace
    ego_lane_index: int
    station_trust: _containers.RepeatedCompositeFieldContainer[StationTrust]
    ego_lane: EgoLane
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., objects: _Optional[_Iterable[_Union[SceneObject, _Mapping]]] = ..., has_mio: _Optional[bool] = ..., mio_id: _Optional[int] = ..., has_forward_mio: _Optional[bool] = ..., forward_mio_id: _Optional[int] = ..., neighbours: _Optional[_Iterable[_Union[LaneNeighbours, _Mapping]]] = ..., free_space: _Optional[_Union[FreeSpace, _Mapping]] = ..., ego_lane_index: _Optional[int] = ..., station_trust: _Optional[_Iterable[_Union[StationTrust, _Mapping]]] = ..., ego_lane: _Optional[_Union[EgoLane, _Mapping]] = ...) -> None: ...

class LaneBoundary(_message.Message):
    __slots__ = ("c0_m", "c1", "c2_1pm", "c3_1pm2", "view_range_m", "confidence")
    C0_M_FIELD_NUMBER: _ClassVar[int]
    C1_FIELD_NUMBER: _ClassVar[int]
    C2_1PM_FIELD_NUMBER: _ClassVar[int]
    C3_1PM2_FIELD_NUMBER: _ClassVar[int]
    VIEW_RANGE_M_FIELD_NUMBER: _ClassVar[int]
    CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    c0_m: float
    c1: float
    c2_1pm: float
    c3_1pm2: float
    view_range_m: float
    confidence: float
    def __init__(self, c0_m: _Optional[float] = ..., c1: _Optional[float] = ..., c2_1pm: _Optional[float] = ..., c3_1pm2: _Optional[float] = ..., view_range_m: _Optional[float] = ..., confidence: _Optional[float] = ...) -> None: ...

class EgoLane(_message.Message):
    __slots__ = ("valid", "lane_index", "lateral_offset_m", "lateral_offset_std_m", "heading_error_rad", "curvature_1pm", "lane_width_m", "source", "left", "right", "map_minus_camera_offset_m")
    VALID_FIELD_NUMBER: _ClassVar[int]
    LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_STD_M_FIELD_NUMBER: _ClassVar[int]
    HEADING_ERROR_RAD_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_1PM_FIELD_NUMBER: _ClassVar[int]
    LANE_WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    SOURCE_FIELD_NUMBER: _ClassVar[int]
    LEFT_FIELD_NUMBER: _ClassVar[int]
    RIGHT_FIELD_NUMBER: _ClassVar[int]
    MAP_MINUS_CAMERA_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    valid: bool
    lane_index: int
    lateral_offset_m: float
    lateral_offset_std_m: float
    heading_error_rad: float
    curvature_1pm: float
    lane_width_m: float
    source: LaneSource
    left: LaneBoundary
    right: LaneBoundary
    map_minus_camera_offset_m: float
    def __init__(self, valid: _Optional[bool] = ..., lane_index: _Optional[int] = ..., lateral_offset_m: _Optional[float] = ..., lateral_offset_std_m: _Optional[float] = ..., heading_error_rad: _Optional[float] = ..., curvature_1pm: _Optional[float] = ..., lane_width_m: _Optional[float] = ..., source: _Optional[_Union[LaneSource, str]] = ..., left: _Optional[_Union[LaneBoundary, _Mapping]] = ..., right: _Optional[_Union[LaneBoundary, _Mapping]] = ..., map_minus_camera_offset_m: _Optional[float] = ...) -> None: ...

class StationTrust(_message.Message):
    __slots__ = ("station_id", "trust", "trusted", "security_failing", "untrusted_signer")
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    TRUST_FIELD_NUMBER: _ClassVar[int]
    TRUSTED_FIELD_NUMBER: _ClassVar[int]
    SECURITY_FAILING_FIELD_NUMBER: _ClassVar[int]
    UNTRUSTED_SIGNER_FIELD_NUMBER: _ClassVar[int]
    station_id: int
    trust: float
    trusted: bool
    security_failing: bool
    untrusted_signer: bool
    def __init__(self, station_id: _Optional[int] = ..., trust: _Optional[float] = ..., trusted: _Optional[bool] = ..., security_failing: _Optional[bool] = ..., untrusted_signer: _Optional[bool] = ...) -> None: ...
