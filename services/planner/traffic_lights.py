"""Traffic lights: a machine beside the scenario's that adds the signalised stop line (and GLOSA's speed) to
whatever the scenario asks for.

Each step it reads the MAPEMs and SPATEMs heard (services/planner/signals/), matches the ego to an ingress lane and
its signal group, and asks `advise` what the phases call for. It stops at the line on red and on amber it can stop
for comfortably, proceeds on amber it cannot (the dilemma zone), goes on green unless the queue ahead leaves no room
past the box (it would strand there), slows to arrive on green (GLOSA), and stops safely when the SPaT of a
signalised approach is stale, contradicts itself or gives no rule, and when the ego matches no lane of a MAP whose
signalised stop line lies ahead near its path. Stopping, it lets go a partner already across the line: the platoon
splits there. Past the stop line it is committed: it clears the box whatever the light.
"""

from __future__ import annotations

import enum

from coopdrive.v1 import planner_pb2
from coopdrive.v2x.timebase import ItsClock

from .config import SignalConfig
from .engine import MachineSpec, StateSpec, Transition, from_each
from .signals.advice import Advice, Advised, Approach, advise, stopping_distance_m
from .signals.awareness import SignalAwareness, SignalStatus, SignalView
from .signals.phases import Light
from .situation import Situation


class LightState(enum.Enum):
    IDLE = enum.auto()
    GO = enum.auto()
    GLOSA = enum.auto()
    STOP = enum.auto()
    COMMITTED = enum.auto()
    SAFE_STOP = enum.auto()


class LightEvent(enum.Enum):
    NO_SIGNAL = enum.auto()
    MAP_MISMATCH = enum.auto()
    CLEARED = enum.auto()
    PASSED_STOP_LINE = enum.auto()
    SPAT_UNUSABLE = enum.auto()
    SPAT_USABLE = enum.auto()
    GREEN = enum.auto()
    GREEN_LATER = enum.auto()
    STOP_REQUIRED = enum.auto()
    AMBER_TOO_CLOSE = enum.auto()
    BOX_EXIT_BLOCKED = enum.auto()


EVENT_OF_ADVICE = {Advice.GO: LightEvent.GREEN, Advice.GLOSA: LightEvent.GREEN_LATER,
                   Advice.STOP: LightEvent.STOP_REQUIRED, Advice.PROCEED: LightEvent.AMBER_TOO_CLOSE,
                   Advice.UNKNOWN: LightEvent.SPAT_UNUSABLE}


class TrafficLights:
    """The machine's context: what this step shows, the guards, and the request's additions."""

    def __init__(self, config: SignalConfig, clock: ItsClock, glosa: bool) -> None:
        self.config = config
        self.glosa = glosa
        self.awareness = SignalAwareness(config, clock)
        self.spec = build_spec()
        self.sit: Situation | None = None
        self.view = SignalView(SignalStatus.NO_MAP)
        self.advised: Advised | None = None
        self.committed_to: tuple[tuple[int, int], int] | None = None
        self._heard: dict[tuple[str, int], float] = {}

    # --- what the step shows
    def _ingest(self, sit: Situation) -> None:
        """Each MAPEM and SPATEM once, in the order received."""
        fresh = [(got.receive_time_s, kind, station, got.message)
                 for kind, table in (("mapem", sit.inputs.mapems), ("spatem", sit.inputs.spatems))
                 for station, got in table.items() if got.receive_time_s > self._heard.get((kind, station), -1.0)]
        for received_s, kind, station, message in sorted(fresh, key=lambda item: (item[0], item[1])):
            self._heard[(kind, station)] = received_s
            if kind == "mapem":
                self.awareness.on_mapem(message)
            else:
                self.awareness.on_spatem(message, received_s)

    def to_stop_line_m(self) -> float | None:
        """From the front bumper to the matched lane's stop line (negative past it), or matched to none, to the
        signalised stop line ahead of us."""
        match, ahead_m = self.view.match, self.view.unmatched_stop_line_m
        rear_m = match.to_stop_line_m if match is not None else ahead_m
        return None if rear_m is None else rear_m - self.config.rear_axle_to_front_m

    def _lane_key(self) -> tuple[tuple[int, int], int] | None:
        match = self.view.match
        return None if match is None else (match.lane.intersection, match.lane.lane_id)

    def observe(self, sit: Situation, limit_mps: float) -> list[enum.Enum]:
        self.sit = sit
        self._ingest(sit)
        ego = sit.inputs.ego
        if ego is None:
            self.view, self.advised = SignalView(SignalStatus.NO_MAP, why="no ego state"), None
        else:
            self.view = self.awareness.view(sit.now_s, ego.latitude_deg, ego.longitude_deg, ego.heading_rad,
                                            self.config.intention)
        E, events = LightEvent, []
        if self._lane_key() != self.committed_to:
            events.append(E.CLEARED)
        if not self.view.on_signalised_lane:
            mismatch = self.view.unmatched_stop_line_m is not None and self.to_stop_line_m() >= 0.0
            return [*events, E.MAP_MISMATCH if mismatch else E.NO_SIGNAL]
        if self.to_stop_line_m() < 0.0:
            return [*events, E.PASSED_STOP_LINE]
        if self.view.status is not SignalStatus.OK:
            self.advised = None
            return [*events, E.SPAT_UNUSABLE]
        approach = Approach(sit.now_s, self.to_stop_line_m(), sit.ego_speed_mps(), limit_mps)
        self.advised = advise(self.view.timing, approach, self.config, self.glosa)
        event = EVENT_OF_ADVICE[self.advised.advice]
        if event in (E.GREEN, E.GREEN_LATER) and self.exit_blocked() and self.can_stop_comfortably():
            event = E.BOX_EXIT_BLOCKED
        return [*events, E.SPAT_USABLE, event]

    def exit_blocked(self) -> bool:
        """The vehicle ahead stands (or crawls) with less room behind it past the stop line than it takes us to
        leave the box: entering on green would strand us in it."""
        mio = self.sit.forward_mio()
        if mio is None or mio.speed_mps.value > self.config.queue_speed_mps:
            return False
        return mio.longitudinal_gap_m - self.to_stop_line_m() < self.config.box_clear_m

    # --- guards and actions
    def can_stop_comfortably(self) -> bool:
        return self.to_stop_line_m() >= stopping_distance_m(self.sit.ego_speed_mps(), self.config)

    def cannot_stop_comfortably(self) -> bool:
        return not self.can_stop_comfortably()

    def commit(self) -> None:
        self.committed_to = self._lane_key()

    def release(self) -> None:
        self.committed_to = None

    # --- the request
    def apply(self, state: enum.Enum, request: planner_pb2.BehaviourRequest) -> None:
        """Adds the stop line (and GLOSA's speed) the state calls for to the scenario's request."""
        S = LightState
        stop = state in (S.STOP, S.SAFE_STOP)
        if state is S.GLOSA and self.advised is not None:
            request.desired_speed_mps = min(request.desired_speed_mps, self.advised.speed_mps)
            current = self.view.timing.current if self.view.timing is not None else None
            stop = current is None or current.light is not Light.GO
        distance_m = self.to_stop_line_m()
        if stop and distance_m is not None:
            if not request.has_stop_line or distance_m < request.stop_line_distance_m:
                request.has_stop_line, request.stop_line_distance_m = True, max(distance_m, 0.0)
            self._split_at_the_line(request, distance_m)

    def _split_at_the_line(self, request: planner_pb2.BehaviourRequest, distance_m: float) -> None:
        """The light changed between us and the vehicle we follow: a predecessor whose rear is already across the
        stop line we stop at is let go, so control follows the line and not a partner driving on, and our iCLCM names
        no forward partner: we head the part of the platoon behind the line."""
        across = [target for target in request.targets if target.role == planner_pb2.TARGET_ROLE_PREDECESSOR
                  and (ahead := self.sit.object(target.object_id)) is not None
                  and ahead.longitudinal_gap_m > distance_m]
        if not across:
            return
        kept = [target for target in request.targets if target not in across]
        del request.targets[:]
        request.targets.extend(kept)
        if request.HasField("iclcm"):
            request.iclcm.forward_id = 0


def build_spec() -> MachineSpec:
    S, E, Ctx = LightState, LightEvent, TrafficLights
    states = (
        StateSpec(S.IDLE, safe=True, description="no signalised ingress lane matched: the scenario drives"),
        # Safe: none waits on anyone; the SPaT's freshness is judged every step and stale SPaT leaves them at once.
        StateSpec(S.GO, safe=True, description="green until we arrive: the scenario drives"),
        StateSpec(S.GLOSA, safe=True,
                  description="slow to arrive on the next green; the stop line kept while it is not green"),
        StateSpec(S.STOP, safe=True, description="red, or amber we can stop for comfortably: stop at the stop line, "
                                                 "letting go a predecessor already across it (the platoon splits)"),
        StateSpec(S.COMMITTED, safe=True, description="past the stop line or too close on amber: clear the box"),
        StateSpec(S.SAFE_STOP, safe=True,
                  description="SPaT stale, contradicting itself or without a rule: stop at the stop line"),
    )
    approaching = [S.IDLE, S.GO, S.GLOSA, S.STOP]
    transitions = (
        Transition(S.IDLE, E.GREEN, S.GO, reason="green until we arrive"),
        Transition(S.GLOSA, E.GREEN, S.GO, reason="green until we arrive"),
        Transition(S.STOP, E.GREEN, S.GO, reason="green"),
        *from_each([S.IDLE, S.GO, S.STOP], E.GREEN_LATER, S.GLOSA, reason="GLOSA: a later green can be reached"),
        *from_each([S.IDLE, S.GO, S.GLOSA], E.STOP_REQUIRED, S.STOP, reason="red, or amber with room to stop"),
        *from_each([S.IDLE, S.GO, S.GLOSA], E.BOX_EXIT_BLOCKED, S.STOP,
                   reason="green, but the queue ahead leaves no room past the box: do not enter"),
        *from_each([S.IDLE, S.GO, S.GLOSA], E.AMBER_TOO_CLOSE, S.COMMITTED, action=Ctx.commit,
                   reason="amber within the comfortable stopping distance: proceed"),
        Transition(S.GO, E.SPAT_UNUSABLE, S.COMMITTED, guard=Ctx.cannot_stop_comfortably, action=Ctx.commit,
                   reason="SPaT lost on green within the comfortable stopping distance: proceed"),
        *from_each(approaching, E.SPAT_UNUSABLE, S.SAFE_STOP, reason="SPaT unusable on a signalised approach"),
        *from_each(approaching, E.MAP_MISMATCH, S.SAFE_STOP,
                   reason="on no lane of the MAP, a signalised stop line ahead near our path"),
        Transition(S.SAFE_STOP, E.SPAT_USABLE, S.IDLE, reason="SPaT usable again"),
        *from_each([*approaching, S.SAFE_STOP], E.PASSED_STOP_LINE, S.COMMITTED, action=Ctx.commit,
                   reason="past the stop line: clear the box"),
        *from_each([S.GO, S.GLOSA, S.STOP, S.SAFE_STOP], E.NO_SIGNAL, S.IDLE,
                   reason="on no signalised ingress lane"),
        Transition(S.COMMITTED, E.CLEARED, S.IDLE, action=Ctx.release, reason="off the lane committed to"),
    )
    return MachineSpec("traffic_lights", S.IDLE, states, transitions)
