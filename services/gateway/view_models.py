"""Response models of /v2x/stations, /scene, /planner and the live frames of /ws.

Unlike /state (proto3 JSON as is), these are views shaped for operators and the HMI: enums by
short lower-case name, unknown confidences as null, the forward MIO flagged on its object.
"""

from __future__ import annotations

from enum import Enum

from pydantic import BaseModel, Field


class LinkStateName(str, Enum):
    UNSPECIFIED = "unspecified"
    ACTIVE = "active"
    LOST = "lost"


class StationView(BaseModel):
    station_id: int
    state: LinkStateName
    last_heard_s: float = Field(description="Vehicle clock when the station was last heard.")
    message_rate_hz: float
    reception_ratio: float = Field(description="Received over expected messages, [0, 1].")
    expected_cam_rate_hz: float = Field(0.0, description="The rate its CAMs are expected at: a profile's, or the "
                                        "station's own median rate; 0 until known.")
    clock_offset_s: float = Field(0.0, description="Its clock minus ours from its generation times, s (negative: "
                                  "behind; transit included).")
    clock_diagnostic: str = Field("", description="A likely cause when its clock is off by more than transit.")
    update_delay_p50_s: float
    update_delay_p95_s: float
    update_delay_max_s: float
    messages_received: int
    messages_rejected: int
    trust: float = Field(description="Trust in the station, [0, 1].")
    signed: bool = Field(description="Its last packet was signed (ETSI TS 103 097).")
    verified: bool = Field(description="Its last packet's signature was checked and valid.")
    trusted: bool = Field(False, description="Its last packet's signer chains to a root this vehicle trusts.")
    messages_signed: int = 0
    messages_verified: int = 0
    messages_trusted: int = 0
    messages_untrusted: int = Field(0, description="Packets whose signer's chain failed (untrusted, expired...).")
    signature_failures: int = Field(0, description="Packets whose signature was invalid.")
    messages_refused_by_security: int = Field(0, description="Packets the security mode dropped.")
    last_security_reason: str = Field("", description="Why its last packet fell short (a reject reason), or ''.")


class V2xStationsResponse(BaseModel):
    vehicle_id: str
    clock_s: float | None
    age_s: float | None = Field(description="Age of the V2X status on the vehicle clock; null if none received.")
    stations: list[StationView]
    active_count: int
    lost_count: int
    packets_sent: int
    packets_received: int
    rejected_by_reason: dict[str, int]


class PropertyView(BaseModel):
    value: float | None = Field(description="Null when the property is unknown or has faded.")
    confidence: float | None = Field(description="[0, 1]; null when unknown or faded (-1 on the bus).")
    sources: list[str] = Field(description="Sensor sources supporting it now, e.g. ['radar', 'v2v'].")


class PositionView(BaseModel):
    x_m: float | None
    y_m: float | None
    std_m: float
    confidence: float | None
    sources: list[str]


class SceneObjectView(BaseModel):
    object_id: int
    object_class: str = Field(description="'car', 'truck', 'emergency_vehicle', 'obstacle' or 'unspecified'.")
    position: PositionView
    speed_mps: PropertyView
    accel_mps2: PropertyView
    heading_rad: PropertyView
    length_m: PropertyView
    width_m: PropertyView
    lane_index: PropertyView
    station_id: PropertyView
    longitudinal_gap_m: float
    lateral_offset_m: float
    relative_speed_mps: float
    v2v_trust: float
    ghost: bool
    first_seen_s: float
    is_mio: bool
    is_forward_mio: bool


class SceneResponse(BaseModel):
    vehicle_id: str
    clock_s: float | None
    age_s: float | None = Field(description="Age of the scene on the vehicle clock; null if none received.")
    ego_lane_index: int | None = Field(description="0 = rightmost lane; null when not matched to a map.")
    mio_id: int | None
    forward_mio_id: int | None
    objects: list[SceneObjectView]


class TransitionView(BaseModel):
    time_s: float
    from_state: str
    to_state: str
    event: str
    reason: str
    forced: bool


class PlannerResponse(BaseModel):
    vehicle_id: str
    clock_s: float | None
    age_s: float | None
    scenario: str | None = Field(description="'follow', 'platoon', 'merge', 'intersection', 'emergency'.")
    machine: str | None
    state: str | None
    time_in_state_s: float | None
    recent_transitions: list[TransitionView]
    graph_mermaid: str | None = Field(description="Mermaid text of the machine's graph, the latest one sent.")


class LiveObject(BaseModel):
    id: int
    x_m: float = Field(description="Ahead of the ego rear axle, ego frame.")
    y_m: float = Field(description="Left of the ego rear axle, ego frame.")
    heading_rad: float = Field(description="Relative to the ego heading.")
    length_m: float
    width_m: float
    confidence: float = Field(description="Position confidence, 0 when unknown.")
    object_class: str
    station_id: int | None
    forward_mio: bool
    v2v_trust: float


class LiveStation(BaseModel):
    station_id: int
    state: LinkStateName
    trust: float
    reception_ratio: float
    signed: bool = False
    verified: bool = False
    trusted: bool = False
    last_security_reason: str = ""


class LiveAvailability(BaseModel):
    mode: str
    available: bool
    unmet_condition: str


class LiveFrame(BaseModel):
    """One frame of /ws: everything the HMI draws, compact."""

    seq: int
    clock_s: float | None
    speed_mps: float | None
    accel_mps2: float | None
    gap_m: float | None = Field(description="Gap to the forward MIO, null without one.")
    time_gap_s: float | None = Field(description="gap_m / speed_mps, null without a gap or when standing.")
    lane_width_m: float
    ego_lane_index: int | None = Field(description="0 = rightmost lane; null when not matched to a map.")
    lateral_offset_m: float
    objects: list[LiveObject]
    stations: list[LiveStation]
    scenario: str | None
    planner_state: str | None
    time_in_state_s: float | None
    mode: str | None
    mode_change_reason: str
    availability: list[LiveAvailability]
    health: dict[str, bool] = Field(description="Service name -> alive.")
