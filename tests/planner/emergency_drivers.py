"""The emergency world (an emergency vehicle coming from behind in the left lane) and a driver for each
declared emergency transition."""

from __future__ import annotations

from drivers import TIMEOUT, Driver, Key, Reach, on_event, on_timeout
from planner_world import EMERGENCY_APPROACHING, denm, ego, emergency_cam, inputs, scene

from coopdrive.services.planner.config import EmergencyConfig
from coopdrive.v1 import planner_pb2

MACHINE = "emergency"
EV = 66


def world(t, ev_east_m=None, offset_m=0.0, lane=1, with_denm=False, heard_at=None,
          scenario=planner_pb2.SCENARIO_EMERGENCY):
    """Us in `lane` at `offset_m` from its centre; the EV's CAM (heard at `heard_at`, now by default) puts it
    `ev_east_m` ahead of us (negative: behind)."""
    cams = {} if ev_east_m is None else {EV: emergency_cam(EV, t if heard_at is None else heard_at, ev_east_m)}
    denms = {EV: denm(EMERGENCY_APPROACHING, origin=EV)} if with_denm else {}
    return inputs(scenario, ego=ego(lane, lateral_offset_m=offset_m), scene=scene(ego_lane=lane), cams=cams,
                  denms=denms)


NORMAL = Reach(world, ((0.0, {}),))
OPENING = NORMAL.then(0.1, ev_east_m=-100.0)
HOLD_CORRIDOR = OPENING.then(0.2, ev_east_m=-80.0, offset_m=0.9)
CLOSING = HOLD_CORRIDOR.then(3.0, ev_east_m=20.0, offset_m=0.9)
# A corridor that could not be opened in time (open_timeout_s 8 s after 0.1 s).
SLOW_SAFE = OPENING.then(8.2, ev_east_m=-60.0)
REACH = {"NORMAL": NORMAL, "OPENING": OPENING, "HOLD_CORRIDOR": HOLD_CORRIDOR, "CLOSING": CLOSING,
         "SLOW_SAFE": SLOW_SAFE}
# Past the passed margin (10 m) ahead of us.
PASSED_EAST_M = 20.0
# The EV's last CAM stays the one heard when the state was reached: lost once lost_after_s has passed.
LOST_AFTER_S = EmergencyConfig().lost_after_s + 0.1


def ev_lost(reach: Reach) -> Driver:
    return on_event(reach, LOST_AFTER_S, heard_at=reach.reached_s)


DRIVERS: dict[Key, Driver] = {
    (MACHINE, "NORMAL", "EV_APPROACHING", "OPENING"): on_event(NORMAL, ev_east_m=-100.0),
    (MACHINE, "OPENING", "CORRIDOR_OPEN", "HOLD_CORRIDOR"): on_event(OPENING, ev_east_m=-80.0, offset_m=0.9),
    # Half way to the edge when the EV goes past.
    (MACHINE, "OPENING", "EV_PASSED", "CLOSING"): on_event(OPENING, ev_east_m=PASSED_EAST_M, offset_m=0.5),
    (MACHINE, "HOLD_CORRIDOR", "EV_PASSED", "CLOSING"): on_event(HOLD_CORRIDOR, 2.8, ev_east_m=PASSED_EAST_M),
    (MACHINE, "HOLD_CORRIDOR", "EV_LOST", "CLOSING"): ev_lost(HOLD_CORRIDOR),
    (MACHINE, "CLOSING", "CORRIDOR_CLOSED", "NORMAL"): on_event(CLOSING, 1.0, ev_east_m=60.0, offset_m=0.1),
    (MACHINE, "SLOW_SAFE", "EV_PASSED", "NORMAL"): on_event(SLOW_SAFE, ev_east_m=PASSED_EAST_M),
    (MACHINE, "SLOW_SAFE", "EV_LOST", "NORMAL"): ev_lost(SLOW_SAFE),
    **{(MACHINE, source, TIMEOUT, "SLOW_SAFE"): on_timeout(REACH[source])
       for source in ("OPENING", "HOLD_CORRIDOR", "CLOSING")},
}
