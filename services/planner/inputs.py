"""What the planner is given each step: the latest estimates and messages, as plain data."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Generic, TypeVar

from coopdrive.v1 import ego_pb2, infrastructure_pb2, its_pb2, planner_pb2, scene_pb2

M = TypeVar("M")


@dataclass(frozen=True)
class Received(Generic[M]):
    """A decoded V2X message and the stack time it was received at."""

    message: M
    receive_time_s: float


@dataclass
class PlannerInputs:
    """Latest ego state, scene and V2X messages (the newest per sending station) and who we are.

    `scenario` and `platoon_id` come from the vehicle's scenario configuration (HMI or launch file);
    the planner switches machine when `scenario` changes.
    """

    station_id: int
    scenario: planner_pb2.Scenario = planner_pb2.SCENARIO_FOLLOW
    # 1 platoon A, 2 platoon B (iCLCM platoonID); 0 when not in a platoon.
    platoon_id: int = 0
    ego: ego_pb2.EgoState | None = None
    scene: scene_pb2.Scene | None = None
    iclcms: dict[int, Received[its_pb2.IclcmContent]] = field(default_factory=dict)
    cams: dict[int, Received[its_pb2.CamContent]] = field(default_factory=dict)
    denms: dict[int, Received[its_pb2.DenmContent]] = field(default_factory=dict)
    # Roadside units' intersection topology and signal phases (traffic lights), by sending station.
    mapems: dict[int, Received[infrastructure_pb2.MapemContent]] = field(default_factory=dict)
    spatems: dict[int, Received[infrastructure_pb2.SpatemContent]] = field(default_factory=dict)
    # Platooning: the station to join behind; 0 = whoever is the forward MIO.
    partner_station_id: int = 0
    # Platooning: the operator or the mission asks to leave the platoon.
    leave_requested: bool = False
