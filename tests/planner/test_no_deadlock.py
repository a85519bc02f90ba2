"""For random message-drop patterns, every machine is back in a safe or terminal state within a bound.

Small reactive worlds stand in for the partners: they answer the planner's iCLCM intent as the GCDC
protocol says, but the messages both ways go through a lossy link drawn by hypothesis (independent
losses plus bursts). Timeouts are shortened so that an example runs in simulated tens of seconds.
"""

from __future__ import annotations

import random

from hypothesis import given, settings
from hypothesis import strategies as st
from planner_world import (EMERGENCY_APPROACHING, ME, ROADWORKS, denm, ego, emergency_cam, iclcm, inputs, obj,
                           rsu_end, rsu_start, scene)

from coopdrive.services.planner.config import PlannerLogicConfig
from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import planner_pb2

DT_S = 0.1
STEPS = 300
LANE_A, LANE_B = 1, 0
PARTNER = 21
NORTH = 1.5707963

FAST = PlannerLogicConfig(
    platoon={"join_timeout_s": 5.0, "leave_timeout_s": 3.0},
    merge={"pairing_timeout_s": 2.0, "head_flag_timeout_s": 6.0, "gap_making_timeout_s": 5.0, "stom_timeout_s": 3.0,
           "merge_wait_timeout_s": 4.0, "lane_change_timeout_s": 5.0, "retry_after_s": 1.0},
    intersection={"organiser_station_ids": [77], "arrival_time_s": 15.0, "approach_timeout_s": 20.0,
                  "give_way_timeout_s": 6.0, "crossing_timeout_s": 8.0, "clear_hold_s": 1.0},
    emergency={"open_timeout_s": 3.0, "hold_timeout_s": 8.0, "close_timeout_s": 3.0, "lost_after_s": 1.0})


class Link:
    """Delivers or drops each message: independent losses at rate `drop` plus loss bursts."""

    def __init__(self, seed: int, drop: float, bursts: list[tuple[int, int]]) -> None:
        self.rng, self.drop, self.bursts = random.Random(seed), drop, bursts

    def delivered(self, step: int) -> bool:
        lost = self.rng.random() < self.drop
        return not lost and not any(start <= step < start + length for start, length in self.bursts)


links = st.builds(Link, st.integers(0, 2**16), st.floats(0.0, 0.7),
                  st.lists(st.tuples(st.integers(0, STEPS), st.integers(1, 60)), max_size=4))


class World:
    def __init__(self, link_in: Link, link_out: Link) -> None:
        self.link_in, self.link_out = link_in, link_out
        self.heard: dict[int, object] = {}
        self.step = 0

    def hear(self, station: int, t: float, **fields) -> None:
        if self.link_in.delivered(self.step):
            self.heard[station] = iclcm(station, t, **fields)


class GapMakerWorld(World):
    def __init__(self, *links) -> None:
        super().__init__(*links)
        self.gap_m, self.partner_lane, self.ack, self.stom_since = 5.0, LANE_A, False, None

    def inputs(self, t):
        self.hear(PARTNER, t, backward_id=ME if self.ack else 0, acknowledge_flag=self.ack)
        objects = [obj(1, 11, 20.0, LANE_B), obj(2, PARTNER, self.gap_m, self.partner_lane)]
        ahead = 2 if self.partner_lane == LANE_A else None
        world = scene(*objects, forward_mio=1, ego_lane=LANE_B, neighbours={1: (ahead, None)})
        return inputs(planner_pb2.SCENARIO_MERGE, ego=ego(LANE_B), scene=world,
                      iclcms={900: rsu_start(t), **self.heard}, denms={900: denm(ROADWORKS)})

    def react(self, t, request, state):
        if self.link_out.delivered(self.step):
            self.ack = self.ack or request.iclcm.forward_id == PARTNER
            if request.iclcm.safe_to_merge and self.stom_since is None:
                self.stom_since = t
        if state in ("GAP_MAKING", "WAIT_MERGE"):
            self.gap_m += 0.5
        if self.stom_since is not None and t - self.stom_since >= 1.0:
            self.partner_lane = LANE_B


class MergerWorld(World):
    def __init__(self, link_in, link_out, head_after_s: float) -> None:
        super().__init__(link_in, link_out)
        self.head_after_s, self.stom, self.merging_since, self.lane = head_after_s, False, None, LANE_A

    def inputs(self, t):
        self.hear(PARTNER, t, forward_id=ME, merge_safe_to_merge=self.stom)
        head = t >= self.head_after_s
        objects = [obj(4, 41, 15.0, LANE_B), obj(3, PARTNER, -10.0, LANE_B)]
        if not head:
            objects.append(obj(5, 51, 20.0, LANE_A))
        world = scene(*objects, forward_mio=None if head else 5, ego_lane=self.lane, neighbours={-1: (4, 3)})
        return inputs(planner_pb2.SCENARIO_MERGE, ego=ego(self.lane), scene=world,
                      iclcms={900: rsu_start(t), **self.heard}, denms={900: denm(ROADWORKS)})

    def react(self, t, request, state):
        if self.link_out.delivered(self.step) and request.iclcm.merge_request:
            self.stom = True
        self.merging_since = (self.merging_since if self.merging_since is not None else t) \
            if state == "MERGING" else None
        if self.merging_since is not None and t - self.merging_since >= 2.0:
            self.lane = LANE_B


class PlatoonWorld(World):
    def __init__(self, link_in, link_out, end_after_s: float) -> None:
        super().__init__(link_in, link_out)
        self.gap_m, self.end_after_s = 40.0, end_after_s

    def inputs(self, t):
        self.hear(PARTNER, t)
        rsu = rsu_end(t) if t >= self.end_after_s else rsu_start(t)
        return inputs(planner_pb2.SCENARIO_PLATOON, platoon_id=2, ego=ego(), iclcms={900: rsu, **self.heard},
                      scene=scene(obj(1, PARTNER, self.gap_m), forward_mio=1))

    def react(self, t, request, state):
        target_m = 6.0 + request.spacing.time_gap_s * 15.0
        self.gap_m += max(-1.0, min(1.0, target_m - self.gap_m))


class IntersectionWorld(World):
    def __init__(self, link_in, link_out, organiser_after_s: float) -> None:
        super().__init__(link_in, link_out)
        self.x_m, self.speed_mps, self.organiser_after_s = -250.0, 15.0, organiser_after_s

    def inputs(self, t):
        y_m = -80.0 + 8.0 * (t - self.organiser_after_s)
        objects = []
        if t >= self.organiser_after_s and y_m < 100.0:
            self.hear(77, t)
            objects.append(obj(9, 77, -self.x_m, x_m=0.0, y_m=y_m, speed_mps=8.0, heading_rad=NORTH))
        return inputs(planner_pb2.SCENARIO_INTERSECTION, ego=ego(speed_mps=self.speed_mps, x_m=self.x_m),
                      scene=scene(*objects), iclcms={900: rsu_start(t), **self.heard})

    def react(self, t, request, state):
        speed = request.desired_speed_mps
        if request.has_stop_line:
            speed = min(speed, max(0.0, request.stop_line_distance_m - 1.0))
        self.speed_mps = speed
        self.x_m += speed * DT_S


class EmergencyWorld(World):
    def __init__(self, link_in, link_out, with_denm: bool) -> None:
        super().__init__(link_in, link_out)
        self.offset_m, self.with_denm = 0.0, with_denm

    def inputs(self, t):
        cams = {}
        if self.link_in.delivered(self.step):
            self.heard[66] = emergency_cam(66, t, -150.0 + 12.0 * t)
        cams.update(self.heard)
        denms = {66: denm(EMERGENCY_APPROACHING, origin=66)} if self.with_denm and t < 20.0 else {}
        return inputs(planner_pb2.SCENARIO_EMERGENCY, ego=ego(1, lateral_offset_m=self.offset_m), scene=scene(),
                      cams=cams, denms=denms)

    def react(self, t, request, state):
        self.offset_m += max(-0.05, min(0.05, request.lateral_offset_m - self.offset_m))


def run_until_bound(world: World) -> None:
    """Steps the planner; fails if an unsafe state outlives its timeout or the unsafe stretch its bound."""
    planner = Planner(FAST)
    outside_since_s = None
    for step in range(STEPS):
        t = round(step * DT_S, 6)
        world.step = step
        request, state = planner.step(t, world.inputs(t))
        spec = planner.machine.spec
        current = spec.state_spec(planner.current_state())
        # Unsafe states form no cycle (test_planner), so the sum of their timeouts bounds any unsafe stretch.
        bound_s = sum(s.timeout_s for s in spec.states if not (s.safe or s.terminal)) + DT_S
        if current.safe or current.terminal:
            outside_since_s = None
        else:
            outside_since_s = t if outside_since_s is None else outside_since_s
            assert state.time_in_state_s <= current.timeout_s + DT_S, (state.state, state.time_in_state_s)
            assert t - outside_since_s <= bound_s, f"unsafe since {outside_since_s} s in {state.state}"
        world.react(t, request, state.state)
    assert outside_since_s is None or STEPS * DT_S - outside_since_s <= bound_s


FAST_PROPERTY = settings(max_examples=8, derandomize=True, deadline=None, database=None)


@FAST_PROPERTY
@given(links, links)
def test_a_gap_maker_never_deadlocks_whatever_messages_are_lost(link_in, link_out):
    run_until_bound(GapMakerWorld(link_in, link_out))


@FAST_PROPERTY
@given(links, links, st.floats(0.0, 30.0))
def test_a_merger_never_deadlocks_whatever_messages_are_lost(link_in, link_out, head_after_s):
    run_until_bound(MergerWorld(link_in, link_out, head_after_s))


@FAST_PROPERTY
@given(links, links, st.floats(5.0, 60.0))
def test_a_platoon_member_never_deadlocks_whatever_messages_are_lost(link_in, link_out, end_after_s):
    run_until_bound(PlatoonWorld(link_in, link_out, end_after_s))


@FAST_PROPERTY
@given(links, links, st.floats(0.0, 25.0))
def test_an_intersection_crossing_never_deadlocks_whatever_messages_are_lost(link_in, link_out, organiser_after_s):
    run_until_bound(IntersectionWorld(link_in, link_out, organiser_after_s))


@FAST_PROPERTY
@given(links, links, st.booleans())
def test_an_emergency_corridor_never_deadlocks_whatever_messages_are_lost(link_in, link_out, with_denm):
    run_until_bound(EmergencyWorld(link_in, link_out, with_denm))


def test_without_losses_the_merge_completes_for_both_roles():
    for world in (GapMakerWorld(Link(0, 0.0, []), Link(1, 0.0, [])),
                  MergerWorld(Link(0, 0.0, []), Link(1, 0.0, []), head_after_s=3.0)):
        planner = Planner(FAST)
        for step in range(STEPS):
            t = round(step * DT_S, 6)
            world.step = step
            request, state = planner.step(t, world.inputs(t))
            world.react(t, request, state.state)
        assert state.state == "DONE", [(x.to_state, x.reason) for x in state.recent_transitions]
