"""What the stacks did about a signalised intersection's roadside-unit fault (spat_loss, spat_time_jump,
map_lane_offset), judged from the truth alone: one reaction per fault and stack vehicle, which the run's verdict
names.

While the fault is on, a stack that reaches the intersection either stands still before its stop line (the safe
stop a planner makes when it cannot trust what the unit says) or crosses the line. A crossing on red fails the run
by itself (signal_metrics' red-light violation), so a crossing named here was on green or amber, with its margin to
red. A stack that was nowhere near the intersection while the fault lasted is named so too: a run test then sees
that its fault went unmet.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Collection, Sequence

from coopdrive.services.sim.fault_config import SIGNAL_FAULTS
from coopdrive.services.sim.scenario_config import RoadsideUnitConfig
from coopdrive.services.sim.signal_metrics import APPROACH_M, STOPPED_MPS, Crossing, SignalFrames, along_m, crossings
from coopdrive.v1 import infrastructure_pb2

_STATE_PREFIX = "MOVEMENT_PHASE_STATE_"


class Reaction(enum.Enum):
    STOPPED_BEFORE_LINE = "stopped before the stop line"
    CROSSED = "crossed without stopping"
    NOT_MET = "not on an approach while the fault lasted"


@dataclass(frozen=True)
class Standstill:
    time_s: float
    # From the front bumper to the stop line.
    before_line_m: float
    state: int


@dataclass(frozen=True)
class FaultReaction:
    fault: str
    vehicle_id: str
    intersection_id: int
    standstill: Standstill | None
    # The first crossing of the intersection's stop line after the fault began: during it, or after the standstill.
    crossing: Crossing | None
    # Crossed without stopping: the least speed from the fault's start to the crossing (how far it slowed).
    slowest_mps: float | None = None

    @property
    def reaction(self) -> Reaction:
        if self.standstill is not None:
            return Reaction.STOPPED_BEFORE_LINE
        return Reaction.CROSSED if self.crossing is not None else Reaction.NOT_MET

    def describe(self) -> str:
        where = f"intersection {self.intersection_id}"
        head = f"{self.fault}: {self.vehicle_id}"
        if self.reaction is Reaction.NOT_MET:
            return f"{head} not on an approach to {where} while the fault lasted"
        if self.standstill is None:
            return (f"{head} crossed the stop line of {where} at {self.crossing.time_s:.1f} s without stopping "
                    f"(slowest {self.slowest_mps:.1f} m/s, {_margin(self.crossing)})")
        stood = self.standstill
        crossed = ("" if self.crossing is None
                   else f", crossed at {self.crossing.time_s:.1f} s ({_margin(self.crossing)})")
        return (f"{head} stopped {stood.before_line_m:.1f} m before the stop line of {where} at {stood.time_s:.1f} s "
                f"({state_name(stood.state)}){crossed}")


def _margin(crossing: Crossing) -> str:
    return "on red" if crossing.red else f"{crossing.amber_margin_s:.1f} s before red"


def state_name(state: int) -> str:
    """A MovementPhaseState in words: 'protected movement allowed'."""
    return infrastructure_pb2.MovementPhaseState.Name(state).removeprefix(_STATE_PREFIX).lower().replace("_", " ")


def fault_reactions(faults: Sequence, units: Sequence[RoadsideUnitConfig], frames: SignalFrames,
                    stack_ids: Collection[str]) -> list[FaultReaction]:
    """Each signal fault's reaction by each stack vehicle, in the order of the faults."""
    intersection_of = {unit.unit_id: unit.intersection.intersection_id for unit in units
                       if unit.intersection is not None}
    every = crossings(frames) if frames else []
    reactions = []
    for fault in faults:
        if not isinstance(fault, SIGNAL_FAULTS) or fault.unit_id not in intersection_of:
            continue
        intersection_id = intersection_of[fault.unit_id]
        label = f"{fault.type} at {fault.unit_id} ({fault.start_s:.1f}-{fault.end_s:.1f} s)"
        for vehicle_id in stack_ids:
            standstill = _first_standstill(frames, vehicle_id, intersection_id, fault)
            after_s = fault.start_s if standstill is None else standstill.time_s
            crossing = next((c for c in every if c.vehicle_id == vehicle_id and c.intersection_id == intersection_id
                             and c.time_s >= after_s), None)
            if standstill is None and crossing is not None and crossing.time_s >= fault.end_s:
                crossing = None
            slowest_mps = None if standstill is not None or crossing is None else _slowest_mps(
                frames, vehicle_id, fault.start_s, crossing.time_s)
            reactions.append(FaultReaction(label, vehicle_id, intersection_id, standstill, crossing, slowest_mps))
    return reactions


def _first_standstill(frames: SignalFrames, vehicle_id: str, intersection_id: int, fault) -> Standstill | None:
    """The first sample within the fault's time where the vehicle stands on one of the intersection's approaches,
    within APPROACH_M before its stop line."""
    for time_s, vehicles, signals in frames:
        if not fault.active(time_s):
            continue
        vehicle = next((v for v in vehicles if v.vehicle_id == vehicle_id), None)
        if vehicle is None or vehicle.speed_mps >= STOPPED_MPS:
            continue
        for line in signals:
            if line.intersection_id != intersection_id:
                continue
            along = along_m(vehicle, line)
            if along is not None and -APPROACH_M <= along < 0.0:
                return Standstill(time_s, -along, line.state)
    return None


def _slowest_mps(frames: SignalFrames, vehicle_id: str, from_s: float, until_s: float) -> float:
    return min(v.speed_mps for time_s, vehicles, _ in frames if from_s <= time_s <= until_s
               for v in vehicles if v.vehicle_id == vehicle_id)
