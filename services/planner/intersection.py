"""The GCDC intersection: arrive at the competition zone (CZ) on time at 30 km/h, give way, cross.

The organiser's vehicle (and an emergency vehicle, and a competitor further into the CZ) has priority.
A priority vehicle heard on V2V but not in the scene is given way to, until the scene has shown the
conflict area free for a while (scene contradicts V2V): then HOLD_SAFE trusts the scene.
"""

from __future__ import annotations

import enum
import math

from coopdrive.messages.unknowns import UNKNOWN_CONFIDENCE
from coopdrive.v1 import planner_pb2, scene_pb2

from .behaviour import add_target, keep_lane
from .config import Intention, PlannerLogicConfig
from .engine import MachineSpec, StateSpec, Transition, from_each
from .situation import Situation
from .speed_profile import QuinticArrival

# The speed command looks this far along the arrival profile (about the longitudinal response time).
PROFILE_LOOKAHEAD_S = 0.5
# Slower than this a vehicle is standing (waiting at its own stop line), not coming: scene speeds of a
# stopped car are noise around zero.
MOVING_MPS = 0.5
# Paths cross when headings are more than 30 degrees from parallel or antiparallel.
CROSSING_SIN = math.sin(math.radians(30.0))


# A heading within this many standard deviations of a path parallel to ours may be parallel.
HEADING_STDS = 2.0


def surely_crossing(heading: scene_pb2.ScalarProperty, ego_heading_rad: float) -> bool:
    """Whether an object's path crosses ours even where its heading's uncertainty (the scene's std, if it gives
    one) leaves it: at least 30 degrees from parallel and from antiparallel, HEADING_STDS stds in.

    A car passing the other way that a sensor starts a new track on beside us has a heading out of a few
    positions only, a fraction of a radian either way: taken as it stood it crossed our path, and the safety
    circle braked us at 6 m/s2 for a car in its own lane (intersection seeds 5, 6 and 10-13)."""
    from_axis_rad = abs(math.remainder(heading.value - ego_heading_rad, math.pi))
    return math.sin(max(0.0, from_axis_rad - HEADING_STDS * heading.std)) > CROSSING_SIN


class CrossState(enum.Enum):
    IDLE = enum.auto()
    APPROACH = enum.auto()
    GIVE_WAY = enum.auto()
    CROSSING = enum.auto()
    HOLD_SAFE = enum.auto()
    EXITED = enum.auto()


class CrossEvent(enum.Enum):
    START = enum.auto()
    CZ_ENTERED = enum.auto()
    CONFLICT = enum.auto()
    PATH_CLEAR = enum.auto()
    SCENE_CONTRADICTS_V2V = enum.auto()
    PATH_CLEAR_BY_SCENE = enum.auto()
    CROSSED = enum.auto()
    END_OF_SCENARIO = enum.auto()


class IntersectionScenario:
    scenario = planner_pb2.SCENARIO_INTERSECTION

    def __init__(self, config: PlannerLogicConfig) -> None:
        self.config = config
        self.spec = build_spec(config)
        self.sit: Situation | None = None
        self.last_now_s: float | None = None
        self.distance_travelled_cz_m = 0.0
        self.counter_intersection = 0
        self.v2v_only_since_s: float | None = None
        self.scene_clear_since_s: float | None = None
        self.conflicting: list[int] = []
        self.v2v_only: list[int] = []

    # --- geometry
    def _reference_vector(self) -> tuple[float, float]:
        ego, c = self.sit.inputs.ego, self.config.intersection
        if ego is None:
            return math.inf, 0.0
        return c.reference_x_m - ego.x_m, c.reference_y_m - ego.y_m

    def distance_to_reference_m(self) -> float:
        return math.hypot(*self._reference_vector())

    def reference_ahead(self) -> bool:
        dx, dy = self._reference_vector()
        heading = self.sit.inputs.ego.heading_rad if self.sit.inputs.ego is not None else 0.0
        return dx * math.cos(heading) + dy * math.sin(heading) > 0

    def in_zone(self) -> bool:
        return self.distance_to_reference_m() <= self.config.intersection.competition_zone_radius_m

    # --- guards
    def has_conflict(self) -> bool:
        return bool(self.conflicting)

    def has_no_conflict(self) -> bool:
        return not self.conflicting

    def before_stop_line(self) -> bool:
        return self.reference_ahead() and self.distance_to_reference_m() > self.config.intersection.box_half_size_m

    def seen_conflict_before_stop_line(self) -> bool:
        """Only a conflict the scene confirms stops a crossing: HOLD_SAFE let it cross on the scene's word,
        so a V2V-only conflict here would cycle CROSSING -> HOLD_SAFE -> CROSSING."""
        return any(s not in self.v2v_only for s in self.conflicting) and self.before_stop_line()

    # --- what the step shows
    def _priority_stations(self) -> list[int]:
        c, sit = self.config.intersection, self.sit
        stations = set(c.organiser_station_ids) | set(sit.emergency_stations())
        for station, got in sit.inputs.iclcms.items():
            if station != sit.inputs.station_id and got.message.distance_travelled_cz_m > self.distance_travelled_cz_m:
                if sit.iclcm(station) is not None:
                    stations.add(station)
        return sorted(stations)

    def _object_conflicts(self, obj) -> bool:
        c = self.config.intersection
        if c.intention is Intention.STRAIGHT and self._on_our_road(obj):
            return False
        px, py = obj.position.x_m, obj.position.y_m
        dx, dy = c.reference_x_m - px, c.reference_y_m - py
        distance = math.hypot(dx, dy)
        heading, speed = obj.heading_rad.value, obj.speed_mps.value
        approaching = speed > MOVING_MPS and dx * math.cos(heading) + dy * math.sin(heading) > 0
        return distance < c.conflict_radius_m and (approaching or distance < c.safety_circle_m)

    def _update_conflicts(self) -> None:
        sit = self.sit
        self.conflicting, self.v2v_only = [], []
        for station in self._priority_stations():
            obj = sit.object_of_station(station)
            if obj is not None:
                if self._object_conflicts(obj):
                    self.conflicting.append(station)
            elif station in self.config.intersection.organiser_station_ids and not sit.silent(station):
                self.conflicting.append(station)
                self.v2v_only.append(station)

    def _on_our_road(self, obj) -> bool:
        """Moving parallel or antiparallel to us: ahead, behind or in the other lane of our road. Going
        straight on, its path never crosses ours."""
        ego = self.sit.inputs.ego
        moving = obj.speed_mps.value > MOVING_MPS
        return ego is not None and moving and abs(math.sin(obj.heading_rad.value - ego.heading_rad)) <= CROSSING_SIN

    def _scene_clear(self) -> bool:
        """No object of the scene conflicts, whatever V2V says."""
        return not any(self._object_conflicts(o) for o in self.sit.objects())

    def _within_safety_circle(self) -> list:
        """Objects ahead with some of their body inside the safety circle that stand or whose path crosses ours
        (a car coming towards us has its front, not its rear, nearest). A car passing in its own lane the other
        way, or one driving ahead in ours (the forward MIO, followed anyway), is no reason to stop."""
        ego, r = self.sit.inputs.ego, self.config.intersection.safety_circle_m
        if ego is None:
            return []

        def in_the_way(o) -> bool:
            if o.speed_mps.confidence == UNKNOWN_CONFIDENCE:
                # A sonar's echo: something is at our side (Chalmers 4.3.1), which our LiDAR, radar or camera would
                # see if it stood in our path. Its speed, unknown, read 0 here: intersection seed 7 braked at 6 m/s2
                # for the flank of a car passing the other way in its own lane.
                return False
            standing = o.speed_mps.value <= MOVING_MPS
            return standing or surely_crossing(o.heading_rad, ego.heading_rad)

        return [o for o in self.sit.objects() if o.longitudinal_gap_m > 0 and in_the_way(o)
                and self.sit.distance_to_body_m(o, ego.x_m, ego.y_m) < r]

    def observe(self, sit: Situation, state: enum.Enum, time_in_state_s: float) -> list[enum.Enum]:
        self.sit = sit
        if self.last_now_s is not None and self.in_zone() and state is not CrossState.IDLE:
            self.distance_travelled_cz_m += sit.ego_speed_mps() * max(0.0, sit.now_s - self.last_now_s)
        self.last_now_s = sit.now_s
        heard = [r.message.counter_intersection for r in sit.inputs.iclcms.values()]
        self.counter_intersection = max([self.counter_intersection, *heard])
        self._update_conflicts()
        self.v2v_only_since_s = _since(self.v2v_only_since_s, bool(self.v2v_only), sit.now_s)
        self.scene_clear_since_s = _since(self.scene_clear_since_s, self._scene_clear(), sit.now_s)
        hold_s = self.config.intersection.clear_hold_s
        E, events = CrossEvent, []
        if sit.rsu_end():
            events.append(E.END_OF_SCENARIO)
        if sit.rsu_start():
            events.append(E.START)
        if self.in_zone():
            events.append(E.CZ_ENTERED)
        events.append(E.CONFLICT if self.conflicting else E.PATH_CLEAR)
        if self.v2v_only_since_s is not None and sit.now_s - self.v2v_only_since_s >= hold_s:
            events.append(E.SCENE_CONTRADICTS_V2V)
        if self.scene_clear_since_s is not None and sit.now_s - self.scene_clear_since_s >= hold_s:
            events.append(E.PATH_CLEAR_BY_SCENE)
        if not self.reference_ahead() and self.distance_to_reference_m() >= self.config.intersection.box_half_size_m:
            events.append(E.CROSSED)
        return events

    def count_crossing(self) -> None:
        """Only a vehicle past the box has crossed: the scenario's end is no crossing to announce."""
        self.counter_intersection += 1

    def behaviour(self, state: enum.Enum) -> planner_pb2.BehaviourRequest:
        S, sit, c = CrossState, self.sit, self.config.intersection
        # The scenario's end does not clear the intersection: a vehicle that has not crossed still gives way to
        # a priority vehicle the scene shows coming (only to one the scene shows: nothing leaves EXITED).
        gives_way_after_the_end = state is S.EXITED and self.seen_conflict_before_stop_line()
        if state is S.APPROACH:
            request = self._approach()
        elif state in (S.GIVE_WAY, S.HOLD_SAFE) or gives_way_after_the_end:
            request = keep_lane(sit, c.arrival_speed_mps, self.config.platoon.acc_time_gap_s)
            if self.before_stop_line():
                request.has_stop_line = True
                request.stop_line_distance_m = self.distance_to_reference_m() - c.box_half_size_m
            for station in self.conflicting:
                add_target(request, sit.object_of_station(station), planner_pb2.TARGET_ROLE_YIELD, c.safety_circle_m)
        elif state is S.CROSSING:
            request = keep_lane(sit, c.speed_limit_mps, self.config.platoon.acc_time_gap_s)
            close = self._within_safety_circle()
            for obj in close:
                add_target(request, obj, planner_pb2.TARGET_ROLE_YIELD, c.safety_circle_m)
            if close:
                request.desired_speed_mps = 0.0
        else:
            speed = c.speed_limit_mps if state is S.EXITED else c.arrival_speed_mps
            request = keep_lane(sit, speed, self.config.platoon.acc_time_gap_s)
        request.iclcm.distance_travelled_cz_m = self.distance_travelled_cz_m
        request.iclcm.intention = int(c.intention)
        request.iclcm.counter_intersection = self.counter_intersection
        return request

    def _approach(self) -> planner_pb2.BehaviourRequest:
        sit, c = self.sit, self.config.intersection
        to_zone_m = max(0.0, self.distance_to_reference_m() - c.competition_zone_radius_m)
        duration_s = c.arrival_time_s - sit.now_s if c.arrival_time_s > 0 else 0.0
        ego = sit.inputs.ego
        accel = ego.accel_mps2 if ego is not None else 0.0
        profile = QuinticArrival.plan(to_zone_m, duration_s, sit.ego_speed_mps(), accel, c.arrival_speed_mps)
        speed = c.arrival_speed_mps if profile is None else profile.speed_mps(PROFILE_LOOKAHEAD_S)
        request = keep_lane(sit, min(max(speed, 0.0), c.speed_limit_mps), self.config.platoon.acc_time_gap_s)
        if profile is not None:
            request.has_arrival = True
            request.arrival_station_m = (ego.lane.station_m if ego is not None else 0.0) + to_zone_m
            request.arrival_time_s = c.arrival_time_s
            request.arrival_speed_mps = c.arrival_speed_mps
        return request


def _since(since_s: float | None, holds: bool, now_s: float) -> float | None:
    """Since when a condition has held without a break; None when it does not hold now."""
    if not holds:
        return None
    return now_s if since_s is None else since_s


def build_spec(config: PlannerLogicConfig) -> MachineSpec:
    S, E, c = CrossState, CrossEvent, config.intersection
    Ctx = IntersectionScenario
    states = (
        StateSpec(S.IDLE, safe=True, description="keep lane at the arrival speed, wait for the RSU"),
        StateSpec(S.APPROACH, timeout_s=c.approach_timeout_s, escape=S.HOLD_SAFE,
                  description="quintic speed profile to the CZ at the given time and 30 km/h"),
        StateSpec(S.GIVE_WAY, waiting=True, timeout_s=c.give_way_timeout_s, escape=S.HOLD_SAFE,
                  description="stop line, yield to the priority vehicles"),
        StateSpec(S.CROSSING, timeout_s=c.crossing_timeout_s, escape=S.HOLD_SAFE,
                  description="as fast as allowed, 7.5 m safety circle"),
        StateSpec(S.HOLD_SAFE, safe=True, description="hold at the stop line, follow the MIO; cross on a clear scene"),
        StateSpec(S.EXITED, safe=True, terminal=True,
                  description="crossed, or the scenario ended (then still giving way before the stop line)"),
    )
    transitions = (
        Transition(S.IDLE, E.START, S.APPROACH, reason="RSU startPlatoon"),
        Transition(S.APPROACH, E.CZ_ENTERED, S.GIVE_WAY, guard=Ctx.has_conflict,
                   reason="in the CZ, a priority vehicle is coming"),
        Transition(S.APPROACH, E.CZ_ENTERED, S.CROSSING, guard=Ctx.has_no_conflict, reason="in the CZ, way clear"),
        # To HOLD_SAFE, not GIVE_WAY: a flickering conflict must not cycle between two unsafe states.
        Transition(S.CROSSING, E.CONFLICT, S.HOLD_SAFE, guard=Ctx.seen_conflict_before_stop_line,
                   reason="a priority vehicle is coming before the stop line"),
        Transition(S.GIVE_WAY, E.PATH_CLEAR, S.CROSSING, reason="no priority vehicle coming"),
        Transition(S.GIVE_WAY, E.SCENE_CONTRADICTS_V2V, S.HOLD_SAFE,
                   reason="priority vehicle heard on V2V but not in the scene"),
        Transition(S.HOLD_SAFE, E.PATH_CLEAR_BY_SCENE, S.CROSSING, reason="the scene shows the way clear"),
        Transition(S.CROSSING, E.CROSSED, S.EXITED, action=Ctx.count_crossing, reason="past the intersection box"),
        *from_each([S.IDLE, S.APPROACH, S.HOLD_SAFE], E.END_OF_SCENARIO, S.EXITED, reason="RSU endOfScenario"),
    )
    return MachineSpec("intersection", S.IDLE, states, transitions)
