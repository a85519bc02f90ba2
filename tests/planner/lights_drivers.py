"""The traffic lights' world (signal_world: us coming from the west to the stop line at x = -10 m) and a driver
for each declared transition of the traffic lights' machine, which the planner runs beside the scenario's."""

from __future__ import annotations

from dataclasses import dataclass

from drivers import Driven, Driver, Key, Reach, on_event
from planner_world import inputs, obj, scene
from signal_world import AMBER, DARK, GREEN, RED, ego_at, heard, light, mapem

from coopdrive.services.planner.planner import Planner
from coopdrive.v1 import planner_pb2

MACHINE = "traffic_lights"
CONFIG = {"cruise_speed_mps": 13.9}
OFF_THE_MAP_X_M = -400.0
FAR_X_M = -180.0
# Within the comfortable stopping distance of the line (39 m at 13.9 m/s), short of it.
CLOSE_X_M = -30.0
IN_THE_BOX_X_M = -5.0
PAST_THE_BOX_X_M = 40.0
RED_THEN_GREEN_SOON = ((RED, 15.0), (GREEN, 45.0))
RED_LONG = ((RED, 60.0), (GREEN, 90.0))
GREEN_LONG = ((GREEN, 60.0),)
GREEN_ENDING_SOON = ((GREEN, 5.0), (AMBER, 8.0), (RED, 20.0), (GREEN, 50.0))
AMBER_NOW = ((AMBER, 3.0), (RED, 30.0))


def world(t, x_m, phases=GREEN_LONG, spat_at_s=None, spat=True, map_shift_m=0.0, queue_gap_m=None):
    """The MAP (heard at 0 s, or now when its lane is shifted north by map_shift_m) and (unless spat is False)
    group 1's phases, heard at spat_at_s (default now); a car standing queue_gap_m ahead, if given."""
    spatems = heard(light(*phases), t if spat_at_s is None else spat_at_s) if spat else {}
    mapems = heard(mapem(map_shift_m), t if map_shift_m else 0.0)
    ahead = scene() if queue_gap_m is None else scene(obj(QUEUE, gap_m=queue_gap_m, speed_mps=0.0), forward_mio=QUEUE)
    return inputs(planner_pb2.SCENARIO_FOLLOW, ego=ego_at(x_m), mapems=mapems, spatems=spatems, scene=ahead)


@dataclass(frozen=True)
class LightsReach(Reach):
    """A Reach whose steps report the traffic lights' machine."""

    def run(self, p: Planner | None = None) -> tuple[Planner, Driven]:
        p, (request, _) = super().run(p)
        return p, (request, p.lights_state(self.reached_s))

    def step(self, p: Planner, t: float, **change) -> Driven:
        request, _ = super().step(p, t, **change)
        return request, p.lights_state(t)


IDLE = LightsReach(world, ((0.0, {"x_m": OFF_THE_MAP_X_M}),), config=CONFIG)
GO = LightsReach(world, ((0.0, {"x_m": FAR_X_M}),), config=CONFIG)
GO_CLOSE = LightsReach(world, ((0.0, {"x_m": CLOSE_X_M - 10.0}),), config=CONFIG)
GLOSA = LightsReach(world, ((0.0, {"x_m": FAR_X_M, "phases": RED_THEN_GREEN_SOON}),), config=CONFIG)
# Slowing, still on green, for the green after the next red.
GLOSA_ON_GREEN = LightsReach(world, ((0.0, {"x_m": FAR_X_M, "phases": GREEN_ENDING_SOON}),), config=CONFIG)
STOP = LightsReach(world, ((0.0, {"x_m": FAR_X_M, "phases": RED_LONG}),), config=CONFIG)
SAFE_STOP = LightsReach(world, ((0.0, {"x_m": FAR_X_M, "spat": False}),), config=CONFIG)
COMMITTED = IDLE.then(0.1, x_m=IN_THE_BOX_X_M)
REACH = {"IDLE": IDLE, "GO": GO, "GLOSA": GLOSA, "STOP": STOP, "SAFE_STOP": SAFE_STOP}
STALE_AT_S = 1.5
QUEUE = 7
# The MAP's lane this far north of the road: two lanes' widths off.
MISMATCH_M = 4.0

DRIVERS: dict[Key, Driver] = {
    (MACHINE, "IDLE", "GREEN", "GO"): on_event(IDLE, x_m=FAR_X_M),
    (MACHINE, "GLOSA", "GREEN", "GO"): on_event(GLOSA, 15.1, x_m=-20.0, phases=((GREEN, 45.0),)),
    (MACHINE, "STOP", "GREEN", "GO"): on_event(STOP, 60.1, x_m=-20.0, phases=((GREEN, 90.0),)),
    (MACHINE, "IDLE", "GREEN_LATER", "GLOSA"): on_event(IDLE, x_m=FAR_X_M, phases=RED_THEN_GREEN_SOON),
    (MACHINE, "GO", "GREEN_LATER", "GLOSA"): on_event(GO, phases=GREEN_ENDING_SOON),
    (MACHINE, "STOP", "GREEN_LATER", "GLOSA"): on_event(STOP, phases=RED_THEN_GREEN_SOON),
    (MACHINE, "IDLE", "STOP_REQUIRED", "STOP"): on_event(IDLE, x_m=FAR_X_M, phases=RED_LONG),
    (MACHINE, "GO", "STOP_REQUIRED", "STOP"): on_event(GO, phases=RED_LONG),
    (MACHINE, "GLOSA", "STOP_REQUIRED", "STOP"): on_event(GLOSA, phases=RED_LONG),
    (MACHINE, "IDLE", "BOX_EXIT_BLOCKED", "STOP"): on_event(IDLE, x_m=-60.0, queue_gap_m=60.0),
    (MACHINE, "GO", "BOX_EXIT_BLOCKED", "STOP"): on_event(GO, queue_gap_m=170.0),
    (MACHINE, "GLOSA", "BOX_EXIT_BLOCKED", "STOP"): on_event(GLOSA, queue_gap_m=170.0),
    (MACHINE, "IDLE", "AMBER_TOO_CLOSE", "COMMITTED"): on_event(IDLE, x_m=CLOSE_X_M, phases=AMBER_NOW),
    (MACHINE, "GO", "AMBER_TOO_CLOSE", "COMMITTED"): on_event(GO_CLOSE, x_m=CLOSE_X_M, phases=AMBER_NOW),
    (MACHINE, "GLOSA", "AMBER_TOO_CLOSE", "COMMITTED"): on_event(GLOSA_ON_GREEN, x_m=CLOSE_X_M, phases=AMBER_NOW),
    (MACHINE, "GO", "SPAT_UNUSABLE", "COMMITTED"): on_event(GO_CLOSE, STALE_AT_S, x_m=CLOSE_X_M, spat_at_s=0.0),
    (MACHINE, "IDLE", "SPAT_UNUSABLE", "SAFE_STOP"): on_event(IDLE, x_m=FAR_X_M, phases=((DARK, None),)),
    **{(MACHINE, source, "SPAT_UNUSABLE", "SAFE_STOP"): on_event(REACH[source], STALE_AT_S, spat_at_s=0.0)
       for source in ("GO", "GLOSA", "STOP")},
    (MACHINE, "SAFE_STOP", "SPAT_USABLE", "IDLE"): on_event(SAFE_STOP, spat=True),
    (MACHINE, "IDLE", "MAP_MISMATCH", "SAFE_STOP"): on_event(IDLE, x_m=FAR_X_M, map_shift_m=MISMATCH_M),
    **{(MACHINE, source, "MAP_MISMATCH", "SAFE_STOP"): on_event(REACH[source], map_shift_m=MISMATCH_M)
       for source in ("GO", "GLOSA", "STOP")},
    (MACHINE, "IDLE", "PASSED_STOP_LINE", "COMMITTED"): on_event(IDLE, x_m=IN_THE_BOX_X_M),
    **{(MACHINE, source, "PASSED_STOP_LINE", "COMMITTED"): on_event(REACH[source], x_m=IN_THE_BOX_X_M)
       for source in ("GO", "GLOSA", "STOP", "SAFE_STOP")},
    **{(MACHINE, source, "NO_SIGNAL", "IDLE"): on_event(REACH[source], x_m=OFF_THE_MAP_X_M)
       for source in ("GO", "GLOSA", "STOP", "SAFE_STOP")},
    (MACHINE, "COMMITTED", "CLEARED", "IDLE"): on_event(COMMITTED, x_m=PAST_THE_BOX_X_M),
}
