"""The intersection world (us driving east to the reference point, the organiser coming north on the side road)
and a driver for each declared intersection transition."""

from __future__ import annotations

import math

from drivers import TIMEOUT, Driver, Key, Reach, on_event, on_timeout
from planner_world import RSU, ego, iclcm, inputs, obj, planner, rsu_end, rsu_start, scene

from coopdrive.v1 import planner_pb2

MACHINE = "intersection"
ORGANISER, COMPETITOR = 77, 55
NORTH = math.pi / 2
CONFIG = {"intersection": {"organiser_station_ids": [ORGANISER], "arrival_time_s": 20.0}}


def cross_planner(**intersection):
    return planner(intersection={**CONFIG["intersection"], **intersection})


def world(t, x_m, organiser_y_m=None, organiser_heard=False, extra=(), start=True, msgs=None,
          organiser_speed_mps=8.0, end=False):
    """We are at `x_m` east of the reference point; the organiser, seen at `organiser_y_m` north of it, is heard."""
    objects = list(extra)
    if organiser_y_m is not None:
        objects.append(obj(9, ORGANISER, gap_m=-x_m, lane=0, x_m=0.0, y_m=organiser_y_m,
                           speed_mps=organiser_speed_mps, heading_rad=NORTH))
    iclcms = {RSU: rsu_end(t) if end else rsu_start(t)} if start else {}
    if organiser_heard or organiser_y_m is not None:
        iclcms[ORGANISER] = iclcm(ORGANISER, t)
    iclcms.update(msgs or {})
    return inputs(planner_pb2.SCENARIO_INTERSECTION, ego=ego(speed_mps=8.0, x_m=x_m), iclcms=iclcms,
                  scene=scene(*objects))


IDLE = Reach(world, ((0.0, {"x_m": -300.0, "start": False}),), config=CONFIG)
APPROACH = Reach(world, ((0.0, {"x_m": -300.0}),), config=CONFIG)
# The organiser seen coming 50 m south of the reference point as we enter the zone.
GIVE_WAY = APPROACH.then(0.1, x_m=-90.0, organiser_y_m=-50.0)
# The organiser heard but never seen: the scene contradicts V2V once clear_hold_s has passed.
GIVE_WAY_TO_THE_UNSEEN = APPROACH.then(0.1, x_m=-90.0, organiser_heard=True)
CROSSING = APPROACH.then(0.1, x_m=-95.0)
# The organiser appears coming while we are still 45 m before the stop line.
HOLD_SAFE = CROSSING.then(0.2, x_m=-60.0, organiser_y_m=-40.0)
REACH = {"IDLE": IDLE, "APPROACH": APPROACH, "GIVE_WAY": GIVE_WAY, "CROSSING": CROSSING, "HOLD_SAFE": HOLD_SAFE}
CLEAR_HOLD_S = 2.0
unseen_for_the_clear_hold = on_event(GIVE_WAY_TO_THE_UNSEEN, CLEAR_HOLD_S, x_m=-80.0)

DRIVERS: dict[Key, Driver] = {
    (MACHINE, "IDLE", "START", "APPROACH"): on_event(IDLE, start=True),
    (MACHINE, "APPROACH", "CZ_ENTERED", "GIVE_WAY"): on_event(APPROACH, x_m=-90.0, organiser_y_m=-50.0),
    (MACHINE, "APPROACH", "CZ_ENTERED", "CROSSING"): on_event(APPROACH, x_m=-95.0),
    (MACHINE, "CROSSING", "CONFLICT", "HOLD_SAFE"): on_event(CROSSING, x_m=-60.0, organiser_y_m=-40.0),
    (MACHINE, "GIVE_WAY", "PATH_CLEAR", "CROSSING"): on_event(GIVE_WAY, x_m=-80.0, organiser_y_m=30.0),
    (MACHINE, "GIVE_WAY", "SCENE_CONTRADICTS_V2V", "HOLD_SAFE"): unseen_for_the_clear_hold,
    # The same step: held on the scene's word, the scene then shows the way clear.
    (MACHINE, "HOLD_SAFE", "PATH_CLEAR_BY_SCENE", "CROSSING"): unseen_for_the_clear_hold,
    (MACHINE, "CROSSING", "CROSSED", "EXITED"): on_event(CROSSING, 1.0, x_m=20.0),
    **{(MACHINE, source, "END_OF_SCENARIO", "EXITED"): on_event(REACH[source], start=True, end=True)
       for source in ("IDLE", "APPROACH", "HOLD_SAFE")},
    **{(MACHINE, source, TIMEOUT, "HOLD_SAFE"): on_timeout(REACH[source])
       for source in ("APPROACH", "GIVE_WAY", "CROSSING")},
}
