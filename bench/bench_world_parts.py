"""Two parts of the simulated world that replaced a general path, each against that path in the same run:

- lane projection's search for the nearest segment: the few segments NearSegments names against the vectorised
  pass over all of a lane's segments (both return the same segment, to the bit; tests/roadmap), at points up to
  12 m beside every lane of both shipped maps;
- a vehicle bus frame: SaturatingPacker against saturating the values in Python and encoding them with cantools
  (the same bytes; tests/can/test_saturating_packer.py), over the frames the simulator sends: feedback, inertial
  and radar object frames.

    python -m bench world_parts
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from rich.console import Console
from rich.table import Table

from bench.figure import Better, Figure, Unit, instruction_ratio, ratio
from bench.instructions_per_call import Workload, per_call
from bench.sizes import sized
from bench.turn_about import cpu_seconds, least_of_turns
from coopdrive.can import frames
from coopdrive.can.frames import VehicleFrame
from coopdrive.can.saturating_packer import SaturatingPacker, saturated_values
from coopdrive.roadmap import RoadMap

MAPS = ("a270", "intersection")
POINTS_PER_LANE = sized(400, 20)
# A frame takes 4 to 10 us: 10,000 of them make a pass of 40 ms or more, where 2,000 (8 ms) moved a speed-up by
# 15 % between two quiet runs of one commit.
FRAMES_REPEATED = sized(10000, 20)
SEED = 20160528
# Passes of each path, turn about.
PASSES = 5
# Inputs of each path whose instructions are counted.
INSTRUCTION_POINTS_PER_LANE = sized(40, 4)
INSTRUCTION_FRAMES = sized(1000, 20)
INSTRUCTION_WORKLOADS = "bench.bench_world_parts:instruction_workloads"
SIMULATED_FRAMES = (VehicleFrame.WHEEL_SPEEDS, VehicleFrame.DYNAMICS, VehicleFrame.PEDALS, VehicleFrame.INERTIAL,
                    VehicleFrame.RADAR_OBJECT)


def per_call_us(calls: list[Callable[[], object]]) -> float:
    """Mean us of this process's CPU per call over the list."""
    def call_each() -> None:
        for call in calls:
            call()
    return 1e6 * cpu_seconds(call_each) / len(calls)


@dataclass(frozen=True)
class Part:
    """A part of the world and the general path it replaced: the same inputs as calls of each."""
    label: str
    general: list[Callable[[], object]]
    now: list[Callable[[], object]]

    @property
    def name(self) -> str:
        return self.label.split(" (", 1)[0]  # without the count of points, which follows the maps

    def general_and_now_us(self) -> list[float]:
        """Both paths turn about, the least pass of each kept (timeit's advice: the others measure the machine's
        other work)."""
        return least_of_turns([lambda: per_call_us(self.general), lambda: per_call_us(self.now)], PASSES)


def projection_parts(rng: np.random.Generator, points_per_lane: int) -> list[Part]:
    parts = []
    for name in MAPS:
        near, full = [], []
        for lane in RoadMap.load(name).lanes:
            stations = rng.uniform(0.0, lane.length_m, points_per_lane)
            for station, offset in zip(stations, rng.uniform(-12.0, 12.0, points_per_lane)):
                x_m, y_m, _ = lane.pose_at(station, offset)
                # A cell's candidates are worked out the first time a point falls in it, here before timing: a
                # vehicle meets a cell once and then projects a point in it for a dozen steps.
                if lane._near.candidates(x_m, y_m) is not None:
                    near.append(lambda lane=lane, x=x_m, y=y_m: lane._nearest_of(lane._near.candidates(x, y), x, y))
                full.append(lambda lane=lane, x=x_m, y=y_m: lane._nearest_of_all(x, y))
        parts.append(Part(f"nearest lane segment, {name} ({len(full)} points)", full, near))
    return parts


def frame_parts(rng: np.random.Generator, repeated: int) -> list[Part]:
    parts = []
    for frame in SIMULATED_FRAMES:
        definition = frames.message(frame)
        packer = SaturatingPacker(definition)
        samples = [{s.name: float(rng.uniform(s.minimum, s.maximum)) for s in definition.signals}
                   for _ in range(repeated)]
        cantools = [lambda v=v, d=definition: d.encode(saturated_values(d, v), strict=False) for v in samples]
        ours = [lambda v=v, p=packer: p.pack(v) for v in samples]
        parts.append(Part(f"{frame.value} payload", cantools, ours))
    return parts


def parts(points_per_lane: int = POINTS_PER_LANE, frames_repeated: int = FRAMES_REPEATED) -> list[Part]:
    rng = np.random.default_rng(SEED)
    return projection_parts(rng, points_per_lane) + frame_parts(rng, frames_repeated)


def instruction_workloads() -> list[Workload]:
    """Each part's two paths on fewer inputs, for bench/instructions_per_call.py: a count needs no repeats to
    settle, and callgrind runs the calls some fifty times slower."""
    return [workload for part in parts(INSTRUCTION_POINTS_PER_LANE, INSTRUCTION_FRAMES)
            for workload in (Workload(f"{part.name}: general", part.general), Workload(f"{part.name}: now", part.now))]


def main() -> list[Figure]:
    instructions = per_call(INSTRUCTION_WORKLOADS)
    table = Table(title="simulated world: each part against the general path it replaced (same results)")
    for column in ("part", "general path us", "now us", "speed-up", "speed-up in instructions"):
        table.add_column(column, justify="right")
    figures = []
    for part in parts():
        before_us, now_us = part.general_and_now_us()
        counted = None if instructions is None else instruction_ratio(
            f"{part.name}: speed-up", instructions[f"{part.name}: general"] / instructions[f"{part.name}: now"],
            f"{part.name}: general path", Better.HIGHER)
        table.add_row(part.label, f"{before_us:.2f}", f"{now_us:.2f}", f"{before_us / now_us:.1f}",
                      "not counted" if counted is None else f"{counted.value:.1f}")
        figures += [Figure(f"{part.name}: now", now_us, Unit.US)] + ([] if counted is None else [counted])
        figures.append(ratio(f"{part.name}: speed-up", before_us / now_us, f"{part.name}: general path",
                             Better.HIGHER, guarded_by=None if counted is None else counted.name))
    Console().print(table)
    return figures


if __name__ == "__main__":
    main()
