"""The merge worlds (a lane B gap maker, a lane A merger) and a driver for each declared merge transition."""

from __future__ import annotations

from drivers import TIMEOUT, Driver, Key, Reach, on_event, on_timeout
from planner_world import ME, ROADWORKS, RSU, denm, ego, iclcm, inputs, obj, rsu_end, rsu_start, scene

from coopdrive.services.planner.config import MergeConfig
from coopdrive.v1 import planner_pb2

MACHINE = "merge"
A_PARTNER, B_PARTNER, B_AHEAD, A_AHEAD, B_MIO = 21, 31, 41, 51, 11
# A station that is neither us nor anyone in the scene: a partner naming it is paired elsewhere.
ELSEWHERE = 4242
LANE_A, LANE_B = 1, 0
ACKED = {"backward_id": ME, "acknowledge_flag": True}
NAMED = {"forward_id": ME}
STOM = {**NAMED, "merge_safe_to_merge": True}


def gap_maker(t, partner_msg=None, partner_gap_m=5.0, partner_lane=LANE_A, heard_at=None, start=True,
              roadworks=True, partner=True, end=False):
    """In lane B behind B_MIO; A_PARTNER `partner_gap_m` ahead in lane A sends `partner_msg`."""
    msgs = {}
    if start:
        msgs[RSU] = rsu_end(t) if end else rsu_start(t)
    if partner:
        msgs[A_PARTNER] = iclcm(A_PARTNER, t if heard_at is None else heard_at, **(partner_msg or {}))
    objects = [obj(1, B_MIO, 20.0, LANE_B)]
    if partner:
        objects.append(obj(2, A_PARTNER, partner_gap_m, partner_lane))
    world = scene(*objects, forward_mio=1, ego_lane=LANE_B, neighbours={1: (2 if partner else None, None)})
    return inputs(planner_pb2.SCENARIO_MERGE, platoon_id=2, ego=ego(LANE_B), scene=world, iclcms=msgs,
                  denms={RSU: denm(ROADWORKS)} if roadworks else {})


def merger(t, partner_msg=None, head=False, ego_lane=LANE_A, heard_at=None, partner=True, end=False,
           partner_gap_m=-10.0):
    """In lane A behind A_AHEAD (none with `head`); B_PARTNER `partner_gap_m` from us in lane B."""
    msgs = {RSU: rsu_end(t) if end else rsu_start(t)}
    if partner:
        msgs[B_PARTNER] = iclcm(B_PARTNER, t if heard_at is None else heard_at, **(partner_msg or {}))
    objects = [obj(4, B_AHEAD, 15.0, LANE_B)]
    if partner:
        objects.append(obj(3, B_PARTNER, partner_gap_m, LANE_B))
    if not head:
        objects.append(obj(5, A_AHEAD, 20.0, LANE_A))
    world = scene(*objects, forward_mio=None if head else 5, ego_lane=ego_lane,
                  neighbours={-1: (4, 3 if partner else None)})
    return inputs(planner_pb2.SCENARIO_MERGE, platoon_id=1, ego=ego(ego_lane), scene=world, iclcms=msgs,
                  denms={RSU: denm(ROADWORKS)})


# Gap maker: IDLE before the RSU start and the works, PLATOONING, then PAIRING on the works' DENM.
IDLE = Reach(gap_maker, ((0.0, {"start": False, "roadworks": False}),))
PLATOONING = IDLE.then(0.1, roadworks=False)
PAIRING = PLATOONING.then(0.2)
GAP_MAKING = PAIRING.then(0.3, partner_msg=ACKED)
WAIT_MERGE = GAP_MAKING.then(0.4, partner_msg=ACKED, partner_gap_m=25.0)
SAFE_KEEP_LANE = GAP_MAKING.then(0.8, partner_msg=ACKED, heard_at=0.3)
# Merger: the RSU start and the works at once (IDLE -> PLATOONING -> PAIRING in the first step).
MERGER_PAIRING = Reach(merger, ((0.0, {}), (0.1, {})))
WAIT_HEAD = MERGER_PAIRING.then(0.2, partner_msg=NAMED)
WAIT_STOM = WAIT_HEAD.then(0.3, partner_msg=NAMED, head=True)
MERGING = WAIT_STOM.then(0.4, partner_msg=STOM, head=True)
REACH = {"IDLE": IDLE, "PLATOONING": PLATOONING, "PAIRING": PAIRING, "GAP_MAKING": GAP_MAKING,
         "WAIT_MERGE": WAIT_MERGE, "SAFE_KEEP_LANE": SAFE_KEEP_LANE, "WAIT_HEAD": WAIT_HEAD,
         "WAIT_STOM": WAIT_STOM, "MERGING": MERGING}
PARTNER_STATES = ("PAIRING", "GAP_MAKING", "WAIT_MERGE", "WAIT_HEAD", "WAIT_STOM")
GAP_MAKER_STATES = ("PAIRING", "GAP_MAKING", "WAIT_MERGE")
SILENT_AFTER_S = 0.5
# Beyond the side tolerance (5 m) on the wrong side: a forward partner behind us, a backward one ahead.
WRONG_SIDE_GAP_M = 20.0


def partner_silent(source: str) -> Driver:
    return on_event(REACH[source], SILENT_AFTER_S, heard_at=REACH[source].reached_s)


def partner_on_the_wrong_side(source: str) -> Driver:
    sign = -1.0 if source in GAP_MAKER_STATES else 1.0
    return on_event(REACH[source], partner_gap_m=sign * WRONG_SIDE_GAP_M)


DRIVERS: dict[Key, Driver] = {
    (MACHINE, "IDLE", "START_PLATOON", "PLATOONING"): on_event(IDLE, start=True),
    (MACHINE, "IDLE", "ROADWORKS", "PAIRING"): on_event(IDLE, roadworks=True),
    (MACHINE, "PLATOONING", "ROADWORKS", "PAIRING"): on_event(PLATOONING, roadworks=True),
    (MACHINE, "PAIRING", "NO_PARTNER", "DONE"): on_event(PAIRING, partner_msg={"backward_id": ELSEWHERE}),
    (MACHINE, "PAIRING", "NO_PARTNER", "WAIT_HEAD"): on_event(MERGER_PAIRING, partner_msg={"forward_id": ELSEWHERE}),
    (MACHINE, "PAIRING", "PAIRED", "GAP_MAKING"): on_event(PAIRING, partner_msg=ACKED),
    (MACHINE, "PAIRING", "PAIRED", "WAIT_HEAD"): on_event(MERGER_PAIRING, partner_msg=NAMED),
    (MACHINE, "GAP_MAKING", "GAP_OPEN", "WAIT_MERGE"): on_event(GAP_MAKING, partner_gap_m=25.0),
    (MACHINE, "WAIT_MERGE", "PARTNER_MERGED", "DONE"): on_event(WAIT_MERGE, partner_lane=LANE_B),
    (MACHINE, "WAIT_HEAD", "HEAD_FLAG_OURS", "WAIT_STOM"): on_event(WAIT_HEAD, head=True),
    (MACHINE, "WAIT_STOM", "STOM_RECEIVED", "MERGING"): on_event(WAIT_STOM, partner_msg=STOM),
    (MACHINE, "MERGING", "IN_TARGET_LANE", "DONE"): on_event(MERGING, ego_lane=LANE_B),
    (MACHINE, "SAFE_KEEP_LANE", "RETRY", "PAIRING"): on_event(SAFE_KEEP_LANE, MergeConfig().retry_after_s,
                                                             partner_msg=None, heard_at=None),
    **{(MACHINE, source, "PARTNER_LOST", "SAFE_KEEP_LANE"): partner_silent(source) for source in PARTNER_STATES},
    **{(MACHINE, source, "SCENE_CONTRADICTS_V2V", "SAFE_KEEP_LANE"): partner_on_the_wrong_side(source)
       for source in PARTNER_STATES},
    (MACHINE, "IDLE", "END_OF_SCENARIO", "DONE"): on_event(IDLE, start=True, end=True),
    **{(MACHINE, source, "END_OF_SCENARIO", "DONE"): on_event(REACH[source], end=True)
       for source in ("PLATOONING", "SAFE_KEEP_LANE", *PARTNER_STATES)},
    **{(MACHINE, source, TIMEOUT, "SAFE_KEEP_LANE"): on_timeout(REACH[source])
       for source in (*PARTNER_STATES, "MERGING")},
}
