"""A signal group's phases on the stack clock, read from a SPATEM's MovementEvents."""

from __future__ import annotations

import enum
from dataclasses import dataclass

from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v2x.timebase import ItsClock

from .time_mark import stack_time_of_mark_s


class Light(enum.Enum):
    """What a MovementPhaseState asks of a vehicle at the stop line."""

    GO = enum.auto()
    AMBER = enum.auto()
    STOP = enum.auto()
    # Dark, unavailable, flashing amber: the SPaT gives no rule to plan with.
    UNKNOWN = enum.auto()


LIGHT_OF_STATE = {
    pb.MOVEMENT_PHASE_STATE_PERMISSIVE_MOVEMENT_ALLOWED: Light.GO,
    pb.MOVEMENT_PHASE_STATE_PROTECTED_MOVEMENT_ALLOWED: Light.GO,
    # ETSI TS 103 301 maps amber to the clearance states and red-amber to pre-movement (still no entry).
    pb.MOVEMENT_PHASE_STATE_PERMISSIVE_CLEARANCE: Light.AMBER,
    pb.MOVEMENT_PHASE_STATE_PROTECTED_CLEARANCE: Light.AMBER,
    pb.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN: Light.STOP,
    pb.MOVEMENT_PHASE_STATE_STOP_THEN_PROCEED: Light.STOP,
    pb.MOVEMENT_PHASE_STATE_PRE_MOVEMENT: Light.STOP,
}


@dataclass(frozen=True)
class Phase:
    state: int
    light: Light
    # Stack times; None where the sender gave none.
    min_end_s: float | None
    likely_end_s: float | None
    max_end_s: float | None

    @property
    def end_s(self) -> float | None:
        """When it most likely ends: likelyTime, else minEndTime, else maxEndTime."""
        return next((t for t in (self.likely_end_s, self.min_end_s, self.max_end_s) if t is not None), None)

    @property
    def earliest_end_s(self) -> float | None:
        """The soonest it may end: minEndTime, else likelyTime, else maxEndTime."""
        return next((t for t in (self.min_end_s, self.likely_end_s, self.max_end_s) if t is not None), None)

    def contradiction(self, tolerance_s: float) -> str:
        """Why its own timing cannot be true, or ''."""
        low, likely, high = self.min_end_s, self.likely_end_s, self.max_end_s
        if low is not None and high is not None and low > high + tolerance_s:
            return "minEndTime after maxEndTime"
        if likely is not None and ((low is not None and likely < low - tolerance_s)
                                   or (high is not None and likely > high + tolerance_s)):
            return "likelyTime outside minEndTime..maxEndTime"
        return ""


@dataclass(frozen=True)
class GroupTiming:
    """One SPATEM's word on a signal group: its current phase first, then those announced after it."""

    received_s: float
    phases: tuple[Phase, ...]
    # The intersection said it is failing, off or has no valid SPaT.
    failed: bool

    @property
    def current(self) -> Phase | None:
        return self.phases[0] if self.phases else None

    def windows(self, now_s: float) -> list[tuple[Light, float, float | None]]:
        """(light, start, end) of each phase, the current one from now_s; a phase after one with no known end
        cannot be placed and ends the list."""
        out, start_s = [], now_s
        for phase in self.phases:
            out.append((phase.light, start_s, phase.end_s))
            if phase.end_s is None:
                break
            start_s = phase.end_s
        return out


def group_timing(group: pb.SignalGroupState, failed: bool, received_s: float, clock: ItsClock) -> GroupTiming:
    def stack_s(event: pb.MovementEvent, field: str) -> float | None:
        return stack_time_of_mark_s(getattr(event, field), received_s, clock) if event.HasField(field) else None

    phases = tuple(Phase(e.state, LIGHT_OF_STATE.get(e.state, Light.UNKNOWN), stack_s(e, "min_end_time_s"),
                         stack_s(e, "likely_time_s"), stack_s(e, "max_end_time_s")) for e in group.events)
    return GroupTiming(received_s, phases, failed)


def intersection_failed(status: pb.IntersectionStatus) -> bool:
    return (status.failure_flash or status.failure_mode or status.off
            or status.no_valid_spat_is_available_at_this_time)
