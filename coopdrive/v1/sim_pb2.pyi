from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class SimClock(_message.Message):
    __slots__ = ("header", "step", "time_s", "step_s", "lockstep", "participants", "sequences")
    class SequencesEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: int
        def __init__(self, key: _Optional[str] = ..., value: _Optional[int] = ...) -> None: ...
    HEADER_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    STEP_S_FIELD_NUMBER: _ClassVar[int]
    LOCKSTEP_FIELD_NUMBER: _ClassVar[int]
    PARTICIPANTS_FIELD_NUMBER: _ClassVar[int]
    SEQUENCES_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    step: int
    time_s: float
    step_s: float
    lockstep: bool
    participants: _containers.RepeatedScalarFieldContainer[str]
    sequences: _containers.ScalarMap[str, int]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., step: _Optional[int] = ..., time_s: _Optional[float] = ..., step_s: _Optional[float] = ..., lockstep: _Optional[bool] = ..., participants: _Optional[_Iterable[str]] = ..., sequences: _Optional[_Mapping[str, int]] = ...) -> None: ...

class StepDone(_message.Message):
    __slots__ = ("header", "step", "service", "next_step", "sequences")
    class SequencesEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: int
        def __init__(self, key: _Optional[str] = ..., value: _Optional[int] = ...) -> None: ...
    HEADER_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    SERVICE_FIELD_NUMBER: _ClassVar[int]
    NEXT_STEP_FIELD_NUMBER: _ClassVar[int]
    SEQUENCES_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    step: int
    service: str
    next_step: int
    sequences: _containers.ScalarMap[str, int]
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., step: _Optional[int] = ..., service: _Optional[str] = ..., next_step: _Optional[int] = ..., sequences: _Optional[_Mapping[str, int]] = ...) -> None: ...

class VehicleTruth(_message.Message):
    __slots__ = ("vehicle_id", "station_id", "x_m", "y_m", "heading_rad", "speed_mps", "accel_mps2", "yaw_rate_radps", "length_m", "width_m", "lane_index", "station_m", "lateral_offset_m", "steering_angle_rad", "automated")
    VEHICLE_ID_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    HEADING_RAD_FIELD_NUMBER: _ClassVar[int]
    SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    ACCEL_MPS2_FIELD_NUMBER: _ClassVar[int]
    YAW_RATE_RADPS_FIELD_NUMBER: _ClassVar[int]
    LENGTH_M_FIELD_NUMBER: _ClassVar[int]
    WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    STATION_M_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    STEERING_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    AUTOMATED_FIELD_NUMBER: _ClassVar[int]
    vehicle_id: str
    station_id: int
    x_m: float
    y_m: float
    heading_rad: float
    speed_mps: float
    accel_mps2: float
    yaw_rate_radps: float
    length_m: float
    width_m: float
    lane_index: int
    station_m: float
    lateral_offset_m: float
    steering_angle_rad: float
    automated: bool
    def __init__(self, vehicle_id: _Optional[str] = ..., station_id: _Optional[int] = ..., x_m: _Optional[float] = ..., y_m: _Optional[float] = ..., heading_rad: _Optional[float] = ..., speed_mps: _Optional[float] = ..., accel_mps2: _Optional[float] = ..., yaw_rate_radps: _Optional[float] = ..., length_m: _Optional[float] = ..., width_m: _Optional[float] = ..., lane_index: _Optional[int] = ..., station_m: _Optional[float] = ..., lateral_offset_m: _Optional[float] = ..., steering_angle_rad: _Optional[float] = ..., automated: _Optional[bool] = ...) -> None: ...

class GroundTruth(_message.Message):
    __slots__ = ("header", "vehicles", "collisions")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    VEHICLES_FIELD_NUMBER: _ClassVar[int]
    COLLISIONS_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    vehicles: _containers.RepeatedCompositeFieldContainer[VehicleTruth]
    collisions: int
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., vehicles: _Optional[_Iterable[_Union[VehicleTruth, _Mapping]]] = ..., collisions: _Optional[int] = ...) -> None: ...

class RunResult(_message.Message):
    __slots__ = ("header", "scenario", "seed", "success", "failure_reason", "sim_time_s", "wall_time_s", "metrics", "clock_started_monotonic_s", "startup_time_s", "shutdown_time_s")
    class MetricsEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: float
        def __init__(self, key: _Optional[str] = ..., value: _Optional[float] = ...) -> None: ...
    HEADER_FIELD_NUMBER: _ClassVar[int]
    SCENARIO_FIELD_NUMBER: _ClassVar[int]
    SEED_FIELD_NUMBER: _ClassVar[int]
    SUCCESS_FIELD_NUMBER: _ClassVar[int]
    FAILURE_REASON_FIELD_NUMBER: _ClassVar[int]
    SIM_TIME_S_FIELD_NUMBER: _ClassVar[int]
    WALL_TIME_S_FIELD_NUMBER: _ClassVar[int]
    METRICS_FIELD_NUMBER: _ClassVar[int]
    CLOCK_STARTED_MONOTONIC_S_FIELD_NUMBER: _ClassVar[int]
    STARTUP_TIME_S_FIELD_NUMBER: _ClassVar[int]
    SHUTDOWN_TIME_S_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    scenario: str
    seed: int
    success: bool
    failure_reason: str
    sim_time_s: float
    wall_time_s: float
    metrics: _containers.ScalarMap[str, float]
    clock_started_monotonic_s: float
    startup_time_s: float
    shutdown_time_s: float
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., scenario: _Optional[str] = ..., seed: _Optional[int] = ..., success: _Optional[bool] = ..., failure_reason: _Optional[str] = ..., sim_time_s: _Optional[float] = ..., wall_time_s: _Optional[float] = ..., metrics: _Optional[_Mapping[str, float]] = ..., clock_started_monotonic_s: _Optional[float] = ..., startup_time_s: _Optional[float] = ..., shutdown_time_s: _Optional[float] = ...) -> None: ...

class WireMark(_message.Message):
    __slots__ = ("header", "written")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    WRITTEN_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    written: int
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., written: _Optional[int] = ...) -> None: ...

class ServiceFault(_message.Message):
    __slots__ = ("header", "participant", "restart")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    PARTICIPANT_FIELD_NUMBER: _ClassVar[int]
    RESTART_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    participant: str
    restart: bool
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., participant: _Optional[str] = ..., restart: _Optional[bool] = ...) -> None: ...
