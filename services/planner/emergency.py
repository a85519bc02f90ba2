"""Emergency vehicle: open a corridor between the lanes for it, close it once it has passed.

Triggered by a live DENM emergencyVehicleApproaching or by a CAM with the emergency role behind us.
Vehicles in the left lane move to their left edge, the others to their right edge, and slow down.
This machine also serves plain following (SCENARIO_FOLLOW): NORMAL is keep lane, follow the MIO.
"""

from __future__ import annotations

import enum

from coopdrive.v1 import planner_pb2

from .behaviour import keep_lane
from .config import PlannerLogicConfig
from .engine import MachineSpec, StateSpec, Transition
from .situation import Situation


class EmergencyState(enum.Enum):
    NORMAL = enum.auto()
    OPENING = enum.auto()
    HOLD_CORRIDOR = enum.auto()
    CLOSING = enum.auto()
    SLOW_SAFE = enum.auto()


class EmergencyEvent(enum.Enum):
    EV_APPROACHING = enum.auto()
    CORRIDOR_OPEN = enum.auto()
    EV_PASSED = enum.auto()
    EV_LOST = enum.auto()
    CORRIDOR_CLOSED = enum.auto()


class EmergencyScenario:
    scenario = planner_pb2.SCENARIO_EMERGENCY

    def __init__(self, config: PlannerLogicConfig, scenario: int = planner_pb2.SCENARIO_EMERGENCY) -> None:
        self.config = config
        self.scenario = scenario
        self.spec = build_spec(config)
        self.sit: Situation | None = None
        # DENMs (originator, sequence) whose emergency vehicle has been dealt with.
        self.handled_denms: set[tuple[int, int]] = set()
        self.passed_stations: set[int] = set()

    def _live_denm(self):
        denm = self.sit.active_denm(self.config.emergency.denm_cause_code)
        if denm is None or (denm.originating_station_id, denm.sequence_number) in self.handled_denms:
            return None
        return denm

    def _ev_along_m(self, station: int) -> float | None:
        obj = self.sit.object_of_station(station)
        if obj is not None:
            return obj.longitudinal_gap_m
        return self.sit.cam_along_m(station)

    def _vehicles(self) -> list[int]:
        # A CAM older than the loss limit says nothing about where the emergency vehicle is now.
        lost_s = self.config.emergency.lost_after_s
        stations = {s for s in self.sit.emergency_stations() if not self.sit.silent(s, lost_s)}
        denm = self._live_denm()
        if denm is not None:
            stations.add(denm.originating_station_id)
        return sorted(stations - self.passed_stations)

    def mark_handled(self) -> None:
        """Closing the corridor: the messages about this emergency vehicle are dealt with."""
        denm = self.sit.active_denm(self.config.emergency.denm_cause_code)
        if denm is not None:
            self.handled_denms.add((denm.originating_station_id, denm.sequence_number))
        for station in self.sit.emergency_stations():
            along = self._ev_along_m(station)
            if along is None or along > 0:
                self.passed_stations.add(station)

    def _corridor_side(self) -> float:
        return 1.0 if self.sit.ego_lane() >= self.config.emergency.left_of_corridor_lane_index else -1.0

    def observe(self, sit: Situation, state: enum.Enum, time_in_state_s: float) -> list[enum.Enum]:
        self.sit = sit
        e, E = self.config.emergency, EmergencyEvent
        events: list[enum.Enum] = []
        vehicles = self._vehicles()
        alongs = [self._ev_along_m(s) for s in vehicles]
        coming = [a for a in alongs if a is not None and -e.relevance_m <= a <= e.passed_margin_m]
        unknown = any(a is None for a in alongs) and self._live_denm() is not None
        if coming or unknown:
            events.append(E.EV_APPROACHING)
        if vehicles and all(a is not None and a > e.passed_margin_m for a in alongs):
            events.append(E.EV_PASSED)
        heard = any(not sit.silent(s, e.lost_after_s) for s in vehicles)
        if not heard and self._live_denm() is None:
            events.append(E.EV_LOST)
        offset = sit.ego_lateral_offset_m()
        if abs(offset - self._corridor_side() * e.corridor_offset_m) <= e.corridor_settled_m:
            events.append(E.CORRIDOR_OPEN)
        if abs(offset) <= e.corridor_settled_m:
            events.append(E.CORRIDOR_CLOSED)
        return events

    def behaviour(self, state: enum.Enum) -> planner_pb2.BehaviourRequest:
        S, e, sit = EmergencyState, self.config.emergency, self.sit
        if state in (S.OPENING, S.HOLD_CORRIDOR):
            request = keep_lane(sit, e.corridor_speed_mps, self.config.platoon.acc_time_gap_s)
            request.lateral_offset_m = self._corridor_side() * e.corridor_offset_m
            return request
        if state is S.SLOW_SAFE:
            return keep_lane(sit, e.corridor_speed_mps, self.config.platoon.acc_time_gap_s)
        return keep_lane(sit, self.config.cruise_speed_mps, self.config.platoon.acc_time_gap_s)


def build_spec(config: PlannerLogicConfig) -> MachineSpec:
    S, E, e = EmergencyState, EmergencyEvent, config.emergency
    states = (
        StateSpec(S.NORMAL, safe=True, description="keep lane, follow the MIO"),
        StateSpec(S.OPENING, timeout_s=e.open_timeout_s, escape=S.SLOW_SAFE,
                  description="move to the lane's outer edge and slow down"),
        StateSpec(S.HOLD_CORRIDOR, waiting=True, timeout_s=e.hold_timeout_s, escape=S.SLOW_SAFE,
                  description="corridor open, wait for the emergency vehicle to pass"),
        StateSpec(S.CLOSING, timeout_s=e.close_timeout_s, escape=S.SLOW_SAFE,
                  on_enter=EmergencyScenario.mark_handled, description="back to the lane centre"),
        StateSpec(S.SLOW_SAFE, safe=True, description="lane centre, corridor speed, follow the MIO"),
    )
    transitions = (
        Transition(S.NORMAL, E.EV_APPROACHING, S.OPENING, reason="emergency vehicle approaching"),
        Transition(S.OPENING, E.CORRIDOR_OPEN, S.HOLD_CORRIDOR, reason="at the outer edge"),
        Transition(S.OPENING, E.EV_PASSED, S.CLOSING, reason="emergency vehicle passed"),
        Transition(S.HOLD_CORRIDOR, E.EV_PASSED, S.CLOSING, reason="emergency vehicle passed"),
        Transition(S.HOLD_CORRIDOR, E.EV_LOST, S.CLOSING, reason="emergency vehicle no longer heard"),
        Transition(S.CLOSING, E.CORRIDOR_CLOSED, S.NORMAL, reason="back at the lane centre"),
        Transition(S.SLOW_SAFE, E.EV_PASSED, S.NORMAL, action=EmergencyScenario.mark_handled,
                   reason="emergency vehicle passed"),
        Transition(S.SLOW_SAFE, E.EV_LOST, S.NORMAL, action=EmergencyScenario.mark_handled,
                   reason="emergency vehicle no longer heard"),
    )
    return MachineSpec("emergency", S.NORMAL, states, transitions)
