from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class ObjectClass(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    OBJECT_CLASS_UNSPECIFIED: _ClassVar[ObjectClass]
    OBJECT_CLASS_CAR: _ClassVar[ObjectClass]
    OBJECT_CLASS_TRUCK: _ClassVar[ObjectClass]
    OBJECT_CLASS_EMERGENCY_VEHICLE: _ClassVar[ObjectClass]
    OBJECT_CLASS_OBSTACLE: _ClassVar[ObjectClass]

class LaneSide(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LANE_SIDE_UNSPECIFIED: _ClassVar[LaneSide]
    LANE_SIDE_LEFT: _ClassVar[LaneSide]
    LANE_SIDE_RIGHT: _ClassVar[LaneSide]
OBJECT_CLASS_UNSPECIFIED: ObjectClass
OBJECT_CLASS_CAR: ObjectClass
OBJECT_CLASS_TRUCK: ObjectClass
OBJECT_CLASS_EMERGENCY_VEHICLE: ObjectClass
OBJECT_CLASS_OBSTACLE: ObjectClass
LANE_SIDE_UNSPECIFIED: LaneSide
LANE_SIDE_LEFT: LaneSide
LANE_SIDE_RIGHT: LaneSide

class LidarLayer(_message.Message):
    __slots__ = ("layer", "elevation_rad", "azimuth_rad", "range_m")
    LAYER_FIELD_NUMBER: _ClassVar[int]
    ELEVATION_RAD_FIELD_NUMBER: _ClassVar[int]
    AZIMUTH_RAD_FIELD_NUMBER: _ClassVar[int]
    RANGE_M_FIELD_NUMBER: _ClassVar[int]
    layer: int
    elevation_rad: float
    azimuth_rad: _containers.RepeatedScalarFieldContainer[float]
    range_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, layer: _Optional[int] = ..., elevation_rad: _Optional[float] = ..., azimuth_rad: _Optional[_Iterable[float]] = ..., range_m: _Optional[_Iterable[float]] = ...) -> None: ...

class LidarScan(_message.Message):
    __slots__ = ("header", "layers", "max_range_m")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    LAYERS_FIELD_NUMBER: _ClassVar[int]
    MAX_RANGE_M_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    layers: _containers.RepeatedCompositeFieldContainer[LidarLayer]
    max_range_m: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., layers: _Optional[_Iterable[_Union[LidarLayer, _Mapping]]] = ..., max_range_m: _Optional[float] = ...) -> None: ...

class RadarTrack(_message.Message):
    __slots__ = ("track_id", "range_m", "azimuth_rad", "range_rate_mps", "accel_mps2", "width_m")
    TRACK_ID_FIELD_NUMBER: _ClassVar[int]
    RANGE_M_FIELD_NUMBER: _ClassVar[int]
    AZIMUTH_RAD_FIELD_NUMBER: _ClassVar[int]
    RANGE_RATE_MPS_FIELD_NUMBER: _ClassVar[int]
    ACCEL_MPS2_FIELD_NUMBER: _ClassVar[int]
    WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    track_id: int
    range_m: float
    azimuth_rad: float
    range_rate_mps: float
    accel_mps2: float
    width_m: float
    def __init__(self, track_id: _Optional[int] = ..., range_m: _Optional[float] = ..., azimuth_rad: _Optional[float] = ..., range_rate_mps: _Optional[float] = ..., accel_mps2: _Optional[float] = ..., width_m: _Optional[float] = ...) -> None: ...

class RadarTracks(_message.Message):
    __slots__ = ("header", "tracks")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    TRACKS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    tracks: _containers.RepeatedCompositeFieldContainer[RadarTrack]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., tracks: _Optional[_Iterable[_Union[RadarTrack, _Mapping]]] = ...) -> None: ...

class CameraDetection(_message.Message):
    __slots__ = ("detection_id", "object_class", "x_m", "y_m", "width_m", "confidence")
    DETECTION_ID_FIELD_NUMBER: _ClassVar[int]
    OBJECT_CLASS_FIELD_NUMBER: _ClassVar[int]
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    CONFIDENCE_FIELD_NUMBER: _ClassVar[int]
    detection_id: int
    object_class: ObjectClass
    x_m: float
    y_m: float
    width_m: float
    confidence: float
    def __init__(self, detection_id: _Optional[int] = ..., object_class: _Optional[_Union[ObjectClass, str]] = ..., x_m: _Optional[float] = ..., y_m: _Optional[float] = ..., width_m: _Optional[float] = ..., confidence: _Optional[float] = ...) -> None: ...

class LaneMarking(_message.Message):
    __slots__ = ("side", "c0_m", "c1", "c2_1pm", "c3_1pm2", "view_range_m", "quality")
    SIDE_FIELD_NUMBER: _ClassVar[int]
    C0_M_FIELD_NUMBER: _ClassVar[int]
    C1_FIELD_NUMBER: _ClassVar[int]
    C2_1PM_FIELD_NUMBER: _ClassVar[int]
    C3_1PM2_FIELD_NUMBER: _ClassVar[int]
    VIEW_RANGE_M_FIELD_NUMBER: _ClassVar[int]
    QUALITY_FIELD_NUMBER: _ClassVar[int]
    side: LaneSide
    c0_m: float
    c1: float
    c2_1pm: float
    c3_1pm2: float
    view_range_m: float
    quality: float
    def __init__(self, side: _Optional[_Union[LaneSide, str]] = ..., c0_m: _Optional[float] = ..., c1: _Optional[float] = ..., c2_1pm: _Optional[float] = ..., c3_1pm2: _Optional[float] = ..., view_range_m: _Optional[float] = ..., quality: _Optional[float] = ...) -> None: ...

class CameraFrame(_message.Message):
    __slots__ = ("header", "detections", "lane_markings")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    DETECTIONS_FIELD_NUMBER: _ClassVar[int]
    LANE_MARKINGS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    detections: _containers.RepeatedCompositeFieldContainer[CameraDetection]
    lane_markings: _containers.RepeatedCompositeFieldContainer[LaneMarking]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., detections: _Optional[_Iterable[_Union[CameraDetection, _Mapping]]] = ..., lane_markings: _Optional[_Iterable[_Union[LaneMarking, _Mapping]]] = ...) -> None: ...

class SonarRange(_message.Message):
    __slots__ = ("sensor_index", "mount_x_m", "mount_y_m", "mount_yaw_rad", "range_m", "max_range_m", "echo")
    SENSOR_INDEX_FIELD_NUMBER: _ClassVar[int]
    MOUNT_X_M_FIELD_NUMBER: _ClassVar[int]
    MOUNT_Y_M_FIELD_NUMBER: _ClassVar[int]
    MOUNT_YAW_RAD_FIELD_NUMBER: _ClassVar[int]
    RANGE_M_FIELD_NUMBER: _ClassVar[int]
    MAX_RANGE_M_FIELD_NUMBER: _ClassVar[int]
    ECHO_FIELD_NUMBER: _ClassVar[int]
    sensor_index: int
    mount_x_m: float
    mount_y_m: float
    mount_yaw_rad: float
    range_m: float
    max_range_m: float
    echo: bool
    def __init__(self, sensor_index: _Optional[int] = ..., mount_x_m: _Optional[float] = ..., mount_y_m: _Optional[float] = ..., mount_yaw_rad: _Optional[float] = ..., range_m: _Optional[float] = ..., max_range_m: _Optional[float] = ..., echo: _Optional[bool] = ...) -> None: ...

class SonarRanges(_message.Message):
    __slots__ = ("header", "ranges")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    RANGES_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    ranges: _containers.RepeatedCompositeFieldContainer[SonarRange]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., ranges: _Optional[_Iterable[_Union[SonarRange, _Mapping]]] = ...) -> None: ...
