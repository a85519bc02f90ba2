"""The platooning world (a partner ahead, the RSU) and a driver for each declared platooning transition."""

from __future__ import annotations

from drivers import TIMEOUT, Driver, Key, Reach, on_event, on_timeout
from planner_world import RSU, ego, iclcm, inputs, obj, rsu_end, rsu_start, scene

from coopdrive.v1 import planner_pb2

MACHINE = "platooning"
PARTNER = 7
CUT_IN = 2
CLOSE_GAP_M = 13.5  # 6 m + 0.5 s * 15 m/s: the CACC spacing
FAR_GAP_M = 40.0
CUT_IN_GAP_M = 10.0


def platoon_world(t, gap_m=FAR_GAP_M, heard_at=None, start=True, end=False, leave=False, cut_in=False):
    """Platoon B behind PARTNER `gap_m` ahead, heard at `heard_at` (now by default); with `cut_in`, a car
    without V2V between us and the partner is the forward MIO."""
    msgs = {PARTNER: iclcm(PARTNER, t if heard_at is None else heard_at)}
    if start:
        msgs[RSU] = rsu_end(t) if end else rsu_start(t)
    objects = [obj(1, PARTNER, gap_m)]
    if cut_in:
        objects.append(obj(CUT_IN, 0, CUT_IN_GAP_M))
    world = scene(*objects, forward_mio=CUT_IN if cut_in else 1)
    return inputs(planner_pb2.SCENARIO_PLATOON, platoon_id=2, ego=ego(), iclcms=msgs, leave_requested=leave,
                  scene=world)


IDLE = Reach(platoon_world, ((0.0, {"start": False}),))
JOINING = IDLE.then(0.1)
PLATOONING = JOINING.then(0.2, gap_m=CLOSE_GAP_M)
DEGRADED_ACC = PLATOONING.then(0.8, gap_m=CLOSE_GAP_M, heard_at=0.2)
FOLLOW_SAFE = JOINING.then(0.7, heard_at=0.1)
LEAVING = PLATOONING.then(0.3, gap_m=CLOSE_GAP_M, leave=True)
REACH = {"IDLE": IDLE, "JOINING": JOINING, "PLATOONING": PLATOONING, "DEGRADED_ACC": DEGRADED_ACC,
         "FOLLOW_SAFE": FOLLOW_SAFE, "LEAVING": LEAVING}
# The partner's last message stays the one heard when the state was reached: silent 0.5 s later.
SILENT_AFTER_S = 0.5


def partner_silent(source: str) -> Driver:
    return on_event(REACH[source], SILENT_AFTER_S, heard_at=REACH[source].reached_s)


DRIVERS: dict[Key, Driver] = {
    (MACHINE, "IDLE", "START_PLATOON", "JOINING"): on_event(IDLE, start=True),
    (MACHINE, "JOINING", "JOINED", "PLATOONING"): on_event(JOINING, gap_m=CLOSE_GAP_M),
    (MACHINE, "JOINING", "PARTNER_LOST", "FOLLOW_SAFE"): partner_silent("JOINING"),
    (MACHINE, "PLATOONING", "PARTNER_LOST", "DEGRADED_ACC"): partner_silent("PLATOONING"),
    (MACHINE, "JOINING", "SCENE_CONTRADICTS_V2V", "FOLLOW_SAFE"): on_event(JOINING, cut_in=True),
    (MACHINE, "PLATOONING", "SCENE_CONTRADICTS_V2V", "DEGRADED_ACC"): on_event(PLATOONING, cut_in=True),
    (MACHINE, "DEGRADED_ACC", "PARTNER_HEARD", "JOINING"): on_event(DEGRADED_ACC, heard_at=None),
    (MACHINE, "FOLLOW_SAFE", "PARTNER_HEARD", "JOINING"): on_event(FOLLOW_SAFE, heard_at=None),
    (MACHINE, "LEAVING", "GAP_OPENED", "DONE"): on_event(LEAVING, gap_m=50.0),
    **{(MACHINE, source, "LEAVE_REQUESTED", "LEAVING"): on_event(REACH[source], leave=True)
       for source in ("JOINING", "PLATOONING", "DEGRADED_ACC", "FOLLOW_SAFE")},
    **{(MACHINE, source, "END_OF_SCENARIO", "LEAVING"): on_event(REACH[source], start=True, end=True)
       for source in ("IDLE", "JOINING", "PLATOONING", "DEGRADED_ACC", "FOLLOW_SAFE")},
    (MACHINE, "JOINING", TIMEOUT, "FOLLOW_SAFE"): on_timeout(JOINING),
    (MACHINE, "LEAVING", TIMEOUT, "DONE"): on_timeout(LEAVING),
}
