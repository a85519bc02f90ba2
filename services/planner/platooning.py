"""Platooning: join behind a partner, keep the platoon speed and time gap, leave.

The RSU's iCLCM startPlatoon starts it and endOfScenario ends it. Losing the partner's V2V for 400 ms
degrades CACC to ACC with the larger gap (Ploeg et al. 2015) rather than stopping the platoon.
"""

from __future__ import annotations

import enum

from coopdrive.v1 import its_pb2, planner_pb2

from .behaviour import add_target, keep_lane, spacing_m
from .config import PlannerLogicConfig
from .engine import MachineSpec, StateSpec, Transition, from_each
from .situation import Situation

PLATOON_A, PLATOON_B = 1, 2


class PlatoonState(enum.Enum):
    IDLE = enum.auto()
    JOINING = enum.auto()
    PLATOONING = enum.auto()
    DEGRADED_ACC = enum.auto()
    FOLLOW_SAFE = enum.auto()
    LEAVING = enum.auto()
    DONE = enum.auto()


class PlatoonEvent(enum.Enum):
    START_PLATOON = enum.auto()
    PARTNER_HEARD = enum.auto()
    PARTNER_LOST = enum.auto()
    SCENE_CONTRADICTS_V2V = enum.auto()
    JOINED = enum.auto()
    LEAVE_REQUESTED = enum.auto()
    GAP_OPENED = enum.auto()
    END_OF_SCENARIO = enum.auto()


class PlatooningScenario:
    scenario = planner_pb2.SCENARIO_PLATOON

    def __init__(self, config: PlannerLogicConfig) -> None:
        self.config = config
        self.spec = build_spec(config)
        self.sit: Situation | None = None
        self.partner_station_id = 0
        self.started = False

    # --- context for guards and actions
    def choose_partner(self) -> None:
        self.started = True
        wanted = self.sit.inputs.partner_station_id
        self.partner_station_id = wanted or Situation.station_of(self.sit.forward_mio())

    def has_started(self) -> bool:
        return self.started

    def no_cut_in(self) -> bool:
        return not self._cut_in()

    def may_rejoin(self) -> bool:
        return self.started and not self._cut_in()

    def platoon_speed_mps(self) -> float:
        p = self.config.platoon
        platoon_id = self.sit.inputs.platoon_id
        if platoon_id == 0:
            for got in self.sit.inputs.iclcms.values():
                if got.message.HasField("start_platoon"):
                    b = got.message.start_platoon == its_pb2.START_PLATOON_B_AT_60_KPH
                    platoon_id = PLATOON_B if b else PLATOON_A
        return p.platoon_b_speed_mps if platoon_id == PLATOON_B else p.platoon_a_speed_mps

    def _partner_gap_m(self) -> float | None:
        obj = self.sit.object_of_station(self.partner_station_id) or self.sit.forward_mio()
        return obj.longitudinal_gap_m if obj is not None else None

    def _cut_in(self) -> bool:
        """The scene has someone else between us and the V2V partner: CACC on the partner would be blind."""
        partner = self.sit.object_of_station(self.partner_station_id)
        mio = self.sit.forward_mio()
        return partner is not None and mio is not None and mio.object_id != partner.object_id \
            and mio.longitudinal_gap_m < partner.longitudinal_gap_m

    # --- ScenarioLogic
    def observe(self, sit: Situation, state: enum.Enum, time_in_state_s: float) -> list[enum.Enum]:
        self.sit = sit
        if self.partner_station_id == 0 and self.started:
            self.choose_partner()
        events: list[enum.Enum] = []
        if sit.rsu_end():
            events.append(PlatoonEvent.END_OF_SCENARIO)
        if sit.inputs.leave_requested:
            events.append(PlatoonEvent.LEAVE_REQUESTED)
        if sit.rsu_start():
            events.append(PlatoonEvent.START_PLATOON)
        if self.partner_station_id and sit.silent(self.partner_station_id):
            events.append(PlatoonEvent.PARTNER_LOST)
        if self.partner_station_id and not sit.silent(self.partner_station_id):
            events.append(PlatoonEvent.PARTNER_HEARD)
        if self._cut_in():
            events.append(PlatoonEvent.SCENE_CONTRADICTS_V2V)
        gap = self._partner_gap_m()
        p = self.config.platoon
        if gap is not None and abs(gap - spacing_m(sit, p.cacc_time_gap_s)) <= p.join_gap_tolerance_m:
            events.append(PlatoonEvent.JOINED)
        if gap is None or gap >= spacing_m(sit, p.leave_time_gap_s):
            events.append(PlatoonEvent.GAP_OPENED)
        return events

    def behaviour(self, state: enum.Enum) -> planner_pb2.BehaviourRequest:
        sit, p = self.sit, self.config.platoon
        if state is PlatoonState.IDLE:
            return keep_lane(sit, self.config.cruise_speed_mps, p.acc_time_gap_s)
        if state in (PlatoonState.FOLLOW_SAFE, PlatoonState.DEGRADED_ACC, PlatoonState.DONE):
            return keep_lane(sit, self.platoon_speed_mps(), p.acc_time_gap_s)
        gap_s = p.leave_time_gap_s if state is PlatoonState.LEAVING else p.cacc_time_gap_s
        partner = sit.object_of_station(self.partner_station_id)
        # The head sets the platoon's speed; a member follows its partner through the head's speed changes, so
        # a cap at the platoon speed, or at its own cruise speed, would clip every crest of a speed wave.
        speed_mps = self.platoon_speed_mps() if partner is None else max(
            self.platoon_speed_mps(), self.config.cruise_speed_mps) + p.member_speed_headroom_mps
        request = keep_lane(sit, speed_mps, gap_s)
        add_target(request, partner, planner_pb2.TARGET_ROLE_PREDECESSOR)
        request.iclcm.forward_id = self.partner_station_id
        request.iclcm.platoon_id = sit.inputs.platoon_id
        return request


def build_spec(config: PlannerLogicConfig) -> MachineSpec:
    S, E, p = PlatoonState, PlatoonEvent, config.platoon
    states = (
        StateSpec(S.IDLE, safe=True, description="keep lane, follow the MIO, wait for the RSU"),
        StateSpec(S.JOINING, waiting=True, timeout_s=p.join_timeout_s, escape=S.FOLLOW_SAFE,
                  on_enter=PlatooningScenario.choose_partner, description="close up to the CACC gap"),
        StateSpec(S.PLATOONING, safe=True, description="CACC at platoon speed and time gap"),
        StateSpec(S.DEGRADED_ACC, safe=True, description="partner silent: ACC with the larger gap"),
        StateSpec(S.FOLLOW_SAFE, safe=True, description="keep lane, follow the MIO"),
        StateSpec(S.LEAVING, timeout_s=p.leave_timeout_s, escape=S.DONE, description="open the gap"),
        StateSpec(S.DONE, terminal=True, safe=True, description="out of the platoon, follow the MIO"),
    )
    transitions = (
        Transition(S.IDLE, E.START_PLATOON, S.JOINING, reason="RSU startPlatoon"),
        Transition(S.JOINING, E.JOINED, S.PLATOONING, reason="gap within tolerance of the CACC gap"),
        Transition(S.JOINING, E.PARTNER_LOST, S.FOLLOW_SAFE, reason="partner silent for 400 ms"),
        Transition(S.PLATOONING, E.PARTNER_LOST, S.DEGRADED_ACC, reason="partner silent for 400 ms"),
        Transition(S.JOINING, E.SCENE_CONTRADICTS_V2V, S.FOLLOW_SAFE, reason="scene: a vehicle cut in"),
        Transition(S.PLATOONING, E.SCENE_CONTRADICTS_V2V, S.DEGRADED_ACC, reason="scene: a vehicle cut in"),
        Transition(S.DEGRADED_ACC, E.PARTNER_HEARD, S.JOINING, guard=PlatooningScenario.no_cut_in,
                   reason="partner heard again"),
        Transition(S.FOLLOW_SAFE, E.PARTNER_HEARD, S.JOINING, guard=PlatooningScenario.may_rejoin,
                   reason="partner heard again"),
        Transition(S.LEAVING, E.GAP_OPENED, S.DONE, reason="gap opened to the leave time gap"),
        *from_each([S.JOINING, S.PLATOONING, S.DEGRADED_ACC, S.FOLLOW_SAFE], E.LEAVE_REQUESTED, S.LEAVING,
                   reason="leave requested"),
        *from_each([S.IDLE, S.JOINING, S.PLATOONING, S.DEGRADED_ACC, S.FOLLOW_SAFE], E.END_OF_SCENARIO,
                   S.LEAVING, reason="RSU endOfScenario"),
    )
    return MachineSpec("platooning", S.IDLE, states, transitions)
