"""The GCDC merge: lane A closes (road works DENM), its vehicles zip into lane B.

Lane B vehicles (gap makers) pair with the lane A vehicle ahead (forwardID), wait for its acknowledge,
open a gap behind it using it as a second, virtual target and send Safe-To-Merge (STOM). Lane A vehicles
(mergers) acknowledge the B vehicle that names them (backwardID), wait until they hold the head flag
(nobody left ahead in lane A), ask to merge, and change lane on STOM; after the change the head flag is
theirs no more, so it passes to the next A vehicle. The last A vehicle carries mergeFlagTail.

Every waiting state has a timeout, and a silent partner (400 ms) or a scene contradicting the partner's
V2V leaves it at once, to SAFE_KEEP_LANE (keep lane, follow the MIO), which retries while the road works last.
"""

from __future__ import annotations

import enum

from coopdrive.v1 import planner_pb2

from .behaviour import add_target, keep_lane, spacing_m
from .config import PlannerLogicConfig
from .engine import MachineSpec, StateSpec, Transition, from_each
from .platooning import PLATOON_A, PLATOON_B
from .situation import Situation

# A partner counted as ahead (or behind) must be at least this far on that side: a car's length.
SIDE_TOLERANCE_M = 5.0


class MergeRole(enum.Enum):
    GAP_MAKER = enum.auto()
    MERGER = enum.auto()


class MergeState(enum.Enum):
    IDLE = enum.auto()
    PLATOONING = enum.auto()
    PAIRING = enum.auto()
    GAP_MAKING = enum.auto()
    WAIT_MERGE = enum.auto()
    WAIT_HEAD = enum.auto()
    WAIT_STOM = enum.auto()
    MERGING = enum.auto()
    SAFE_KEEP_LANE = enum.auto()
    DONE = enum.auto()


class MergeEvent(enum.Enum):
    START_PLATOON = enum.auto()
    ROADWORKS = enum.auto()
    PAIRED = enum.auto()
    NO_PARTNER = enum.auto()
    GAP_OPEN = enum.auto()
    PARTNER_MERGED = enum.auto()
    HEAD_FLAG_OURS = enum.auto()
    STOM_RECEIVED = enum.auto()
    IN_TARGET_LANE = enum.auto()
    PARTNER_LOST = enum.auto()
    SCENE_CONTRADICTS_V2V = enum.auto()
    RETRY = enum.auto()
    END_OF_SCENARIO = enum.auto()


PARTNER_STATES = (MergeState.PAIRING, MergeState.GAP_MAKING, MergeState.WAIT_MERGE, MergeState.WAIT_HEAD,
                  MergeState.WAIT_STOM)


class MergeScenario:
    scenario = planner_pb2.SCENARIO_MERGE

    def __init__(self, config: PlannerLogicConfig) -> None:
        self.config = config
        self.spec = build_spec(config)
        self.sit: Situation | None = None
        self.state: enum.Enum = MergeState.IDLE
        self.time_in_state_s = 0.0
        self.role = MergeRole.GAP_MAKER
        self.partner_station_id = 0

    # --- lanes and roles
    def _own_lane(self) -> int:
        m = self.config.merge
        return m.lane_a_index if self.role is MergeRole.MERGER else m.lane_b_index

    def _other_lane(self) -> int:
        m = self.config.merge
        return m.lane_b_index if self.role is MergeRole.MERGER else m.lane_a_index

    def _other_offset(self) -> int:
        return 1 if self._other_lane() > self._own_lane() else -1

    def _platoon_id(self) -> int:
        if self.sit.inputs.platoon_id:
            return self.sit.inputs.platoon_id
        return PLATOON_A if self.sit.ego_lane() == self.config.merge.lane_a_index else PLATOON_B

    # --- actions and guards (the scenario is the machine's context)
    def begin_pairing(self) -> None:
        """Role from the lane we are in; partner: ahead in lane A (gap maker) or behind in lane B (merger)."""
        self.role = MergeRole.MERGER if self.sit.ego_lane() == self.config.merge.lane_a_index else MergeRole.GAP_MAKER
        if self.role is MergeRole.GAP_MAKER:
            candidate = Situation.station_of(self.sit.ahead_in_lane(self._other_offset()))
        else:
            candidate = Situation.station_of(self.sit.behind_in_lane(self._other_offset()))
        # Only a station speaking the iCLCM can pair; anyone else is merged around on the scene alone.
        self.partner_station_id = candidate if self.sit.iclcm(candidate) is not None else 0

    def _answer_who_named_us(self) -> None:
        """The protocol pairs a merger with the lane B vehicle that names it as forwardID, wherever the
        scene puts it; of several, the nearest. Only while nobody names us does the scene's choice stand."""
        me = self.sit.inputs.station_id
        namers = [station for station in self.sit.inputs.iclcms
                  if station != me and (msg := self.sit.iclcm(station)) is not None and msg.forward_id == me]
        if not namers or self.partner_station_id in namers:
            return

        def distance_m(station: int) -> float:
            obj = self.sit.object_of_station(station)
            return abs(obj.longitudinal_gap_m) if obj is not None else float("inf")

        self.partner_station_id = min(namers, key=lambda station: (distance_m(station), station))

    def _let_go_of_a_partner_paired_elsewhere(self) -> None:
        """A partner whose iCLCM pairs it with another station will never pair with us: without one, a merger
        merges on the scene's gap and a gap maker has no gap to make, instead of waiting out the timeout
        again and again."""
        msg = self.sit.iclcm(self.partner_station_id) if self.partner_station_id else None
        if msg is None:
            return
        theirs = msg.backward_id if self.role is MergeRole.GAP_MAKER else msg.forward_id
        if theirs not in (0, self.sit.inputs.station_id):
            self.partner_station_id = 0

    def is_gap_maker(self) -> bool:
        return self.role is MergeRole.GAP_MAKER

    def is_merger(self) -> bool:
        return self.role is MergeRole.MERGER

    def roadworks_live(self) -> bool:
        return self.sit.active_denm(self.config.merge.roadworks_cause_code) is not None

    # --- what the step shows
    def _paired(self) -> bool:
        msg = self.sit.iclcm(self.partner_station_id)
        me = self.sit.inputs.station_id
        if msg is None:
            return False
        if self.role is MergeRole.GAP_MAKER:
            return msg.backward_id == me and msg.acknowledge_flag
        return msg.forward_id == me

    def _partner_object(self):
        return self.sit.object_of_station(self.partner_station_id)

    def _contradiction(self) -> bool:
        """The scene puts the partner on the wrong side of us, or in a lane it cannot be in yet."""
        obj = self._partner_object()
        if obj is None or self.state not in PARTNER_STATES:
            return False
        if self.role is MergeRole.GAP_MAKER and obj.longitudinal_gap_m < -SIDE_TOLERANCE_M:
            return True
        if self.role is MergeRole.MERGER and obj.longitudinal_gap_m > SIDE_TOLERANCE_M:
            return True
        lane = Situation.lane_of(obj)
        return self.state is MergeState.PAIRING and lane is not None and lane != self._other_lane()

    def _gap_open(self) -> bool:
        obj = self._partner_object()
        need = spacing_m(self.sit, self.config.platoon.cacc_time_gap_s) + self.config.merge.merge_extra_gap_m
        return obj is not None and obj.longitudinal_gap_m >= need

    def _partner_merged(self) -> bool:
        obj = self._partner_object()
        return obj is not None and Situation.lane_of(obj) == self.sit.ego_lane()

    def _head_flag_ours(self) -> bool:
        mio = self.sit.forward_mio()
        return mio is None or Situation.lane_of(mio) not in (None, self.config.merge.lane_a_index)

    def _stom(self) -> bool:
        if not self._room_beside_and_ahead():
            return False  # STOM vouches for the gap behind us, not for the cars beside and ahead of it
        if self.partner_station_id == 0:
            return self._scene_gap_open()
        msg = self.sit.iclcm(self.partner_station_id)
        return msg is not None and msg.merge_safe_to_merge

    def _alongside(self):
        """The target-lane car beside us, if any. The scene lists it behind us (its rear bumper is behind our
        front one), but a lane change now would end in its flank."""
        behind = self.sit.behind_in_lane(self._other_offset())
        if behind is None:
            return None
        m = self.config.merge
        front_ahead_of_our_rear_m = behind.longitudinal_gap_m + self.sit.length_of_m(behind) + m.ego_length_m
        return behind if front_ahead_of_our_rear_m > -m.side_margin_m else None

    def _room_beside_and_ahead(self) -> bool:
        """Nobody alongside in the target lane (nor felt by the side sonars towards it), and whoever is ahead
        there at least the standstill distance ahead (the lane change's predecessor opens it to a full spacing)."""
        ahead = self.sit.ahead_in_lane(self._other_offset())
        too_close = ahead is not None and ahead.longitudinal_gap_m < self.config.standstill_m
        return not too_close and self._alongside() is None and not self.sit.sonar_beside(self._other_offset())

    def _scene_gap_open(self) -> bool:
        """Without a partner: the scene shows room in the target lane behind. The vehicle behind must be a
        spacing behind at its own speed, and further by what it closes in while we change lane."""
        m, platoon = self.config.merge, self.config.platoon
        behind = self.sit.behind_in_lane(self._other_offset())
        if behind is None:
            return True
        behind_speed_mps = behind.speed_mps.value
        closing_mps = max(0.0, behind_speed_mps - self.sit.ego_speed_mps())
        need_m = (self.config.standstill_m + platoon.cacc_time_gap_s * behind_speed_mps
                  + closing_mps * m.lane_change_duration_s)
        return -behind.longitudinal_gap_m >= need_m

    def roadworks_ahead_m(self) -> float | None:
        """Distance along our heading to the start of the road works closing our lane; None if none ahead."""
        denm = self.sit.active_denm(self.config.merge.roadworks_cause_code)
        if denm is None or self.sit.ego_lane() != self.config.merge.lane_a_index:
            return None
        along = self.sit.along_m(denm.event_position)
        return along if along is not None and along > 0 else None

    def observe(self, sit: Situation, state: enum.Enum, time_in_state_s: float) -> list[enum.Enum]:
        self.sit, self.state, self.time_in_state_s = sit, state, time_in_state_s
        if state is MergeState.PAIRING:
            if self.role is MergeRole.MERGER:
                self._answer_who_named_us()
            self._let_go_of_a_partner_paired_elsewhere()
        E = MergeEvent
        events: list[enum.Enum] = []
        if sit.rsu_end():
            events.append(E.END_OF_SCENARIO)
        if sit.rsu_start():
            events.append(E.START_PLATOON)
        if self.roadworks_live():
            events.append(E.ROADWORKS)
        if state is MergeState.SAFE_KEEP_LANE and time_in_state_s >= self.config.merge.retry_after_s:
            events.append(E.RETRY)
        if state in PARTNER_STATES and self.partner_station_id:
            if sit.silent(self.partner_station_id):
                events.append(E.PARTNER_LOST)
            if self._contradiction():
                events.append(E.SCENE_CONTRADICTS_V2V)
        if state is MergeState.PAIRING and self.partner_station_id == 0:
            events.append(E.NO_PARTNER)
        checks = ((E.PAIRED, self._paired), (E.GAP_OPEN, self._gap_open), (E.PARTNER_MERGED, self._partner_merged),
                  (E.HEAD_FLAG_OURS, self._head_flag_ours), (E.STOM_RECEIVED, self._stom),
                  (E.IN_TARGET_LANE, lambda: sit.ego_lane() == self.config.merge.lane_b_index))
        events.extend(event for event, check in checks if self.partner_station_id or event is not E.PAIRED
                      if check())
        return events

    def behaviour(self, state: enum.Enum) -> planner_pb2.BehaviourRequest:
        S, sit, m = MergeState, self.sit, self.config.merge
        if state in (S.IDLE, S.PLATOONING):
            speed = self.config.platoon.platoon_a_speed_mps if self._platoon_id() == PLATOON_A \
                else self.config.platoon.platoon_b_speed_mps
            if state is S.IDLE:
                speed = self.config.cruise_speed_mps
            request = keep_lane(sit, speed, self.config.platoon.cacc_time_gap_s)
        elif state in (S.SAFE_KEEP_LANE, S.DONE):
            request = keep_lane(sit, m.merge_speed_mps, self.config.platoon.acc_time_gap_s)
        elif state is S.MERGING:
            request = keep_lane(sit, m.merge_speed_mps, self.config.platoon.cacc_time_gap_s, m.lane_b_index)
            request.lane_change_duration_s = m.lane_change_duration_s
            add_target(request, sit.ahead_in_lane(self._other_offset()), planner_pb2.TARGET_ROLE_PREDECESSOR)
        else:
            request = keep_lane(sit, m.merge_speed_mps, self.config.platoon.cacc_time_gap_s)
            if self.role is MergeRole.GAP_MAKER:
                # Heudiasyc: during the merge, platoon w.r.t. the forward MIO in the other lane.
                add_target(request, self._partner_object(), planner_pb2.TARGET_ROLE_VIRTUAL, m.merge_extra_gap_m)
            else:
                add_target(request, sit.ahead_in_lane(self._other_offset()), planner_pb2.TARGET_ROLE_VIRTUAL)
                alongside = self._alongside()
                if alongside is not None:
                    request.desired_speed_mps = min(request.desired_speed_mps,
                                                    max(0.0, alongside.speed_mps.value - m.drop_back_mps))
        works_m = self.roadworks_ahead_m()
        if works_m is not None:
            # Whatever the protocol does, nobody drives into the closed lane's works.
            request.has_stop_line = True
            request.stop_line_distance_m = works_m - m.stop_before_works_m
        self._fill_iclcm(state, request.iclcm)
        return request

    def _fill_iclcm(self, state: enum.Enum, iclcm: planner_pb2.IclcmIntent) -> None:
        S = MergeState
        iclcm.platoon_id = self._platoon_id()
        if state in (S.IDLE, S.PLATOONING, S.SAFE_KEEP_LANE):
            return
        if self.role is MergeRole.GAP_MAKER:
            iclcm.forward_id = self.partner_station_id
            iclcm.safe_to_merge = state is S.WAIT_MERGE
        else:
            iclcm.backward_id = self.partner_station_id
            iclcm.acknowledge = self.partner_station_id != 0
            iclcm.merge_flag_head = state in (S.WAIT_STOM, S.MERGING)
            iclcm.merge_request = state in (S.WAIT_STOM, S.MERGING)
            iclcm.merge_flag = state is S.MERGING
            iclcm.merge_flag_tail = self.sit.behind_in_lane(0) is None


def build_spec(config: PlannerLogicConfig) -> MachineSpec:
    S, E, m = MergeState, MergeEvent, config.merge
    Ctx = MergeScenario
    states = (
        StateSpec(S.IDLE, safe=True, description="keep lane, wait for the RSU"),
        StateSpec(S.PLATOONING, safe=True, description="platoon in the own lane"),
        StateSpec(S.PAIRING, waiting=True, timeout_s=m.pairing_timeout_s, escape=S.SAFE_KEEP_LANE,
                  on_enter=Ctx.begin_pairing, description="forwardID/backwardID, wait for the acknowledge"),
        StateSpec(S.GAP_MAKING, waiting=True, timeout_s=m.gap_making_timeout_s, escape=S.SAFE_KEEP_LANE,
                  description="B: open a gap behind the A partner (virtual target)"),
        StateSpec(S.WAIT_MERGE, waiting=True, timeout_s=m.merge_wait_timeout_s, escape=S.SAFE_KEEP_LANE,
                  description="B: STOM sent, wait for the partner to change lane"),
        StateSpec(S.WAIT_HEAD, waiting=True, timeout_s=m.head_flag_timeout_s, escape=S.SAFE_KEEP_LANE,
                  description="A: wait until nobody is left ahead in lane A"),
        StateSpec(S.WAIT_STOM, waiting=True, timeout_s=m.stom_timeout_s, escape=S.SAFE_KEEP_LANE,
                  description="A: head flag ours, merge request sent, wait for STOM"),
        StateSpec(S.MERGING, timeout_s=m.lane_change_timeout_s, escape=S.SAFE_KEEP_LANE,
                  description="A: change to lane B"),
        StateSpec(S.SAFE_KEEP_LANE, safe=True, description="keep lane, follow the MIO, retry later"),
        StateSpec(S.DONE, safe=True, terminal=True, description="platoon in lane B"),
    )
    transitions = (
        Transition(S.IDLE, E.START_PLATOON, S.PLATOONING, reason="RSU startPlatoon"),
        Transition(S.IDLE, E.ROADWORKS, S.PAIRING, reason="road works DENM"),
        Transition(S.PLATOONING, E.ROADWORKS, S.PAIRING, reason="road works DENM"),
        Transition(S.PAIRING, E.NO_PARTNER, S.DONE, guard=Ctx.is_gap_maker,
                   reason="nobody ahead in lane A: no gap to make"),
        Transition(S.PAIRING, E.NO_PARTNER, S.WAIT_HEAD, guard=Ctx.is_merger,
                   reason="nobody behind in lane B: merge on the scene's gap"),
        Transition(S.PAIRING, E.PAIRED, S.GAP_MAKING, guard=Ctx.is_gap_maker,
                   reason="partner's backwardID is ours and acknowledged"),
        Transition(S.PAIRING, E.PAIRED, S.WAIT_HEAD, guard=Ctx.is_merger, reason="partner's forwardID is ours"),
        Transition(S.GAP_MAKING, E.GAP_OPEN, S.WAIT_MERGE, reason="gap behind the partner open: STOM"),
        Transition(S.WAIT_MERGE, E.PARTNER_MERGED, S.DONE, reason="partner now in our lane"),
        Transition(S.WAIT_HEAD, E.HEAD_FLAG_OURS, S.WAIT_STOM, reason="nobody ahead in lane A: head flag ours"),
        Transition(S.WAIT_STOM, E.STOM_RECEIVED, S.MERGING, reason="safe to merge"),
        Transition(S.MERGING, E.IN_TARGET_LANE, S.DONE, reason="in lane B: head flag passed on"),
        Transition(S.SAFE_KEEP_LANE, E.RETRY, S.PAIRING, guard=Ctx.roadworks_live,
                   reason="retry while the road works last"),
        *from_each(list(PARTNER_STATES), E.PARTNER_LOST, S.SAFE_KEEP_LANE, reason="partner silent for 400 ms"),
        *from_each(list(PARTNER_STATES), E.SCENE_CONTRADICTS_V2V, S.SAFE_KEEP_LANE,
                   reason="scene contradicts the partner's V2V"),
        *from_each([s for s in S if s is not S.MERGING], E.END_OF_SCENARIO, S.DONE, reason="RSU endOfScenario"),
    )
    return MachineSpec("merge", S.IDLE, states, transitions)
