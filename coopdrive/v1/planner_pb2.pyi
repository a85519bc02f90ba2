from coopdrive.v1 import header_pb2 as _header_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class Scenario(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SCENARIO_UNSPECIFIED: _ClassVar[Scenario]
    SCENARIO_FOLLOW: _ClassVar[Scenario]
    SCENARIO_PLATOON: _ClassVar[Scenario]
    SCENARIO_MERGE: _ClassVar[Scenario]
    SCENARIO_INTERSECTION: _ClassVar[Scenario]
    SCENARIO_EMERGENCY: _ClassVar[Scenario]

class TargetRole(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    TARGET_ROLE_UNSPECIFIED: _ClassVar[TargetRole]
    TARGET_ROLE_PREDECESSOR: _ClassVar[TargetRole]
    TARGET_ROLE_VIRTUAL: _ClassVar[TargetRole]
    TARGET_ROLE_YIELD: _ClassVar[TargetRole]
SCENARIO_UNSPECIFIED: Scenario
SCENARIO_FOLLOW: Scenario
SCENARIO_PLATOON: Scenario
SCENARIO_MERGE: Scenario
SCENARIO_INTERSECTION: Scenario
SCENARIO_EMERGENCY: Scenario
TARGET_ROLE_UNSPECIFIED: TargetRole
TARGET_ROLE_PREDECESSOR: TargetRole
TARGET_ROLE_VIRTUAL: TargetRole
TARGET_ROLE_YIELD: TargetRole

class StateTransition(_message.Message):
    __slots__ = ("time_s", "from_state", "to_state", "event", "reason", "forced")
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    FROM_STATE_FIELD_NUMBER: _ClassVar[int]
    TO_STATE_FIELD_NUMBER: _ClassVar[int]
    EVENT_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    FORCED_FIELD_NUMBER: _ClassVar[int]
    time_s: float
    from_state: str
    to_state: str
    event: str
    reason: str
    forced: bool
    def __init__(self, time_s: _Optional[float] = ..., from_state: _Optional[str] = ..., to_state: _Optional[str] = ..., event: _Optional[str] = ..., reason: _Optional[str] = ..., forced: _Optional[bool] = ...) -> None: ...

class PlannerState(_message.Message):
    __slots__ = ("header", "scenario", "machine", "state", "time_in_state_s", "recent_transitions", "graph_mermaid")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    SCENARIO_FIELD_NUMBER: _ClassVar[int]
    MACHINE_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    TIME_IN_STATE_S_FIELD_NUMBER: _ClassVar[int]
    RECENT_TRANSITIONS_FIELD_NUMBER: _ClassVar[int]
    GRAPH_MERMAID_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    scenario: Scenario
    machine: str
    state: str
    time_in_state_s: float
    recent_transitions: _containers.RepeatedCompositeFieldContainer[StateTransition]
    graph_mermaid: str
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., scenario: _Optional[_Union[Scenario, str]] = ..., machine: _Optional[str] = ..., state: _Optional[str] = ..., time_in_state_s: _Optional[float] = ..., recent_transitions: _Optional[_Iterable[_Union[StateTransition, _Mapping]]] = ..., graph_mermaid: _Optional[str] = ...) -> None: ...

class TargetVehicle(_message.Message):
    __slots__ = ("object_id", "station_id", "role", "extra_gap_m")
    OBJECT_ID_FIELD_NUMBER: _ClassVar[int]
    STATION_ID_FIELD_NUMBER: _ClassVar[int]
    ROLE_FIELD_NUMBER: _ClassVar[int]
    EXTRA_GAP_M_FIELD_NUMBER: _ClassVar[int]
    object_id: int
    station_id: int
    role: TargetRole
    extra_gap_m: float
    def __init__(self, object_id: _Optional[int] = ..., station_id: _Optional[int] = ..., role: _Optional[_Union[TargetRole, str]] = ..., extra_gap_m: _Optional[float] = ...) -> None: ...

class SpacingPolicy(_message.Message):
    __slots__ = ("standstill_m", "time_gap_s")
    STANDSTILL_M_FIELD_NUMBER: _ClassVar[int]
    TIME_GAP_S_FIELD_NUMBER: _ClassVar[int]
    standstill_m: float
    time_gap_s: float
    def __init__(self, standstill_m: _Optional[float] = ..., time_gap_s: _Optional[float] = ...) -> None: ...

class IclcmIntent(_message.Message):
    __slots__ = ("forward_id", "backward_id", "acknowledge", "merge_request", "safe_to_merge", "merge_flag", "merge_flag_tail", "merge_flag_head", "platoon_id", "distance_travelled_cz_m", "intention", "counter_intersection", "participants_ready")
    FORWARD_ID_FIELD_NUMBER: _ClassVar[int]
    BACKWARD_ID_FIELD_NUMBER: _ClassVar[int]
    ACKNOWLEDGE_FIELD_NUMBER: _ClassVar[int]
    MERGE_REQUEST_FIELD_NUMBER: _ClassVar[int]
    SAFE_TO_MERGE_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_TAIL_FIELD_NUMBER: _ClassVar[int]
    MERGE_FLAG_HEAD_FIELD_NUMBER: _ClassVar[int]
    PLATOON_ID_FIELD_NUMBER: _ClassVar[int]
    DISTANCE_TRAVELLED_CZ_M_FIELD_NUMBER: _ClassVar[int]
    INTENTION_FIELD_NUMBER: _ClassVar[int]
    COUNTER_INTERSECTION_FIELD_NUMBER: _ClassVar[int]
    PARTICIPANTS_READY_FIELD_NUMBER: _ClassVar[int]
    forward_id: int
    backward_id: int
    acknowledge: bool
    merge_request: bool
    safe_to_merge: bool
    merge_flag: bool
    merge_flag_tail: bool
    merge_flag_head: bool
    platoon_id: int
    distance_travelled_cz_m: float
    intention: int
    counter_intersection: int
    participants_ready: bool
    def __init__(self, forward_id: _Optional[int] = ..., backward_id: _Optional[int] = ..., acknowledge: _Optional[bool] = ..., merge_request: _Optional[bool] = ..., safe_to_merge: _Optional[bool] = ..., merge_flag: _Optional[bool] = ..., merge_flag_tail: _Optional[bool] = ..., merge_flag_head: _Optional[bool] = ..., platoon_id: _Optional[int] = ..., distance_travelled_cz_m: _Optional[float] = ..., intention: _Optional[int] = ..., counter_intersection: _Optional[int] = ..., participants_ready: _Optional[bool] = ...) -> None: ...

class BehaviourRequest(_message.Message):
    __slots__ = ("header", "target_lane_index", "desired_speed_mps", "spacing", "targets", "lateral_offset_m", "lane_change_duration_s", "has_arrival", "arrival_station_m", "arrival_time_s", "arrival_speed_mps", "has_stop_line", "stop_line_distance_m", "iclcm")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    TARGET_LANE_INDEX_FIELD_NUMBER: _ClassVar[int]
    DESIRED_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    SPACING_FIELD_NUMBER: _ClassVar[int]
    TARGETS_FIELD_NUMBER: _ClassVar[int]
    LATERAL_OFFSET_M_FIELD_NUMBER: _ClassVar[int]
    LANE_CHANGE_DURATION_S_FIELD_NUMBER: _ClassVar[int]
    HAS_ARRIVAL_FIELD_NUMBER: _ClassVar[int]
    ARRIVAL_STATION_M_FIELD_NUMBER: _ClassVar[int]
    ARRIVAL_TIME_S_FIELD_NUMBER: _ClassVar[int]
    ARRIVAL_SPEED_MPS_FIELD_NUMBER: _ClassVar[int]
    HAS_STOP_LINE_FIELD_NUMBER: _ClassVar[int]
    STOP_LINE_DISTANCE_M_FIELD_NUMBER: _ClassVar[int]
    ICLCM_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    target_lane_index: int
    desired_speed_mps: float
    spacing: SpacingPolicy
    targets: _containers.RepeatedCompositeFieldContainer[TargetVehicle]
    lateral_offset_m: float
    lane_change_duration_s: float
    has_arrival: bool
    arrival_station_m: float
    arrival_time_s: float
    arrival_speed_mps: float
    has_stop_line: bool
    stop_line_distance_m: float
    iclcm: IclcmIntent
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., target_lane_index: _Optional[int] = ..., desired_speed_mps: _Optional[float] = ..., spacing: _Optional[_Union[SpacingPolicy, _Mapping]] = ..., targets: _Optional[_Iterable[_Union[TargetVehicle, _Mapping]]] = ..., lateral_offset_m: _Optional[float] = ..., lane_change_duration_s: _Optional[float] = ..., has_arrival: _Optional[bool] = ..., arrival_station_m: _Optional[float] = ..., arrival_time_s: _Optional[float] = ..., arrival_speed_mps: _Optional[float] = ..., has_stop_line: _Optional[bool] = ..., stop_line_distance_m: _Optional[float] = ..., iclcm: _Optional[_Union[IclcmIntent, _Mapping]] = ...) -> None: ...

class PlannerForce(_message.Message):
    __slots__ = ("header", "state", "requested_by", "reason")
    HEADER_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    REQUESTED_BY_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    header: _header_pb2.Header
    state: str
    requested_by: str
    reason: str
    def __init__(self, header: _Optional[_Union[_header_pb2.Header, _Mapping]] = ..., state: _Optional[str] = ..., requested_by: _Optional[str] = ..., reason: _Optional[str] = ...) -> None: ...
