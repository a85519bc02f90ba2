"""What the stacks did about a signalised intersection's roadside-unit fault (spat_loss, spat_time_jump,
map_lane_offset), judged from the truth alone: one reaction per fault and stack vehicle, which the run's verdict
names.

While the fault is on, a stack on one of the intersection's approaches (within 200 m of its stop line) either stands
still before the line (the safe stop a planner makes when it cannot trust what the unit says), crosses it, or does
neither (it slowed, say, and the fault ended first): the slowest it went is named. A crossing on red fails the run by
itself (signal_metrics' red-light violation), so a crossing named here was on green or amber, with its margin to
red. A stack that was on no approach while the fault lasted is named so too: a run test then sees that its fault
went unmet.
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
    STOPPED_BEFORE_LINE = enum.auto()
    CROSSED = enum.auto()
    # On an approach, neither stopped nor crossed while the fault lasted.
    APPROACHED = enum.auto()
    NOT_MET = enum.auto()


@dataclass(frozen=True)
class Sample:
    """The vehicle on one of the intersection's approaches, within APPROACH_M before its stop line."""

    time_s: float
    speed_mps: float
    # From the front bumper to the stop line.
    before_line_m: float
    state: int


@dataclass(frozen=True)
class FaultReaction:
    fault: str
    vehicle_id: str
    intersection_id: int
    # The first sample standing still on an approach while the fault lasted.
    standstill: Sample | None
    # The first crossing of the intersection's stop line after the fault began (after the standstill, if any).
    crossing: Crossing | None
    # The least speed on an approach while the fault lasted (before any crossing); None when on none.
    slowest_mps: float | None
    fault_end_s: float

    @property
    def reaction(self) -> Reaction:
        if self.standstill is not None:
            return Reaction.STOPPED_BEFORE_LINE
        if self.crossing is not None and self.crossing.time_s < self.fault_end_s:
            return Reaction.CROSSED
        return Reaction.APPROACHED if self.slowest_mps is not None else Reaction.NOT_MET

    def describe(self) -> str:
        where = f"intersection {self.intersection_id}"
        head = f"{self.fault}: {self.vehicle_id}"
        crossing = self.crossing
        crossed = "" if crossing is None else f", crossed at {crossing.time_s:.1f} s ({_margin(crossing)})"
        reaction = self.reaction
        if reaction is Reaction.NOT_MET:
            return f"{head} not on an approach to {where} while the fault lasted"
        if reaction is Reaction.CROSSED:
            return (f"{head} crossed the stop line of {where} at {crossing.time_s:.1f} s without stopping "
                    f"(slowest {self.slowest_mps:.1f} m/s, {_margin(crossing)})")
        if reaction is Reaction.APPROACHED:
            return (f"{head} on an approach to {where} while the fault lasted, neither stopping nor crossing "
                    f"(slowest {self.slowest_mps:.1f} m/s){crossed}")
        stood = self.standstill
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
            ours = [c for c in every if c.vehicle_id == vehicle_id and c.intersection_id == intersection_id
                    and c.time_s >= fault.start_s]
            samples = _on_approach(frames, vehicle_id, intersection_id, fault,
                                   until_s=ours[0].time_s if ours else fault.end_s)
            standstill = next((sample for sample in samples if sample.speed_mps < STOPPED_MPS), None)
            after_s = fault.start_s if standstill is None else standstill.time_s
            crossing = next((c for c in ours if c.time_s >= after_s), None)
            slowest_mps = min((sample.speed_mps for sample in samples), default=None)
            reactions.append(FaultReaction(label, vehicle_id, intersection_id, standstill, crossing, slowest_mps,
                                           fault.end_s))
    return reactions


def _on_approach(frames: SignalFrames, vehicle_id: str, intersection_id: int, fault, until_s: float
                 ) -> list[Sample]:
    """The vehicle's samples on one of the intersection's approaches, within APPROACH_M before its stop line, while
    the fault lasted and before until_s."""
    found = []
    for time_s, vehicles, signals in frames:
        if not fault.active(time_s) or time_s > until_s:
            continue
        vehicle = next((v for v in vehicles if v.vehicle_id == vehicle_id), None)
        if vehicle is None:
            continue
        for line in signals:
            along = along_m(vehicle, line) if line.intersection_id == intersection_id else None
            if along is not None and -APPROACH_M <= along < 0.0:
                found.append(Sample(time_s, vehicle.speed_mps, -along, line.state))
                break
    return found
