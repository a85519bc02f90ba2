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

import numpy as np
from rich.console import Console
from rich.table import Table

from bench.figure import Better, Figure, Unit, ratio
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
SIMULATED_FRAMES = (VehicleFrame.WHEEL_SPEEDS, VehicleFrame.DYNAMICS, VehicleFrame.PEDALS, VehicleFrame.INERTIAL,
                    VehicleFrame.RADAR_OBJECT)


def per_call_us(calls: list[Callable[[], object]]) -> float:
    """Mean us of this process's CPU per call over the list."""
    def call_each() -> None:
        for call in calls:
            call()
    return 1e6 * cpu_seconds(call_each) / len(calls)


def general_and_now_us(general: list[Callable[[], object]], now: list[Callable[[], object]]) -> list[float]:
    """Both paths turn about, the least pass of each kept (timeit's advice: the others measure the machine's other
    work)."""
    return least_of_turns([lambda: per_call_us(general), lambda: per_call_us(now)], PASSES)


def projection_rows(rng: np.random.Generator) -> list[tuple[str, float, float]]:
    rows = []
    for name in MAPS:
        near, full = [], []
        for lane in RoadMap.load(name).lanes:
            stations = rng.uniform(0.0, lane.length_m, POINTS_PER_LANE)
            for station, offset in zip(stations, rng.uniform(-12.0, 12.0, POINTS_PER_LANE)):
                x_m, y_m, _ = lane.pose_at(station, offset)
                # A cell's candidates are worked out the first time a point falls in it, here before timing: a
                # vehicle meets a cell once and then projects a point in it for a dozen steps.
                if lane._near.candidates(x_m, y_m) is not None:
                    near.append(lambda lane=lane, x=x_m, y=y_m: lane._nearest_of(lane._near.candidates(x, y), x, y))
                full.append(lambda lane=lane, x=x_m, y=y_m: lane._nearest_of_all(x, y))
        rows.append((f"nearest lane segment, {name} ({len(full)} points)", *general_and_now_us(full, near)))
    return rows


def frame_rows(rng: np.random.Generator) -> list[tuple[str, float, float]]:
    rows = []
    for frame in SIMULATED_FRAMES:
        definition = frames.message(frame)
        packer = SaturatingPacker(definition)
        samples = [{s.name: float(rng.uniform(s.minimum, s.maximum)) for s in definition.signals}
                   for _ in range(FRAMES_REPEATED)]
        cantools = [lambda v=v: definition.encode(saturated_values(definition, v), strict=False) for v in samples]
        ours = [lambda v=v: packer.pack(v) for v in samples]
        rows.append((f"{frame.value} payload", *general_and_now_us(cantools, ours)))
    return rows


def main() -> list[Figure]:
    rng = np.random.default_rng(SEED)
    table = Table(title="simulated world: each part against the general path it replaced (same results)")
    for column in ("part", "general path us", "now us", "speed-up"):
        table.add_column(column, justify="right")
    figures = []
    for label, before_us, now_us in projection_rows(rng) + frame_rows(rng):
        table.add_row(label, f"{before_us:.2f}", f"{now_us:.2f}", f"{before_us / now_us:.1f}")
        name = label.split(" (", 1)[0]  # without the count of points, which follows the maps
        figures += [Figure(f"{name}: now", now_us, Unit.US),
                    ratio(f"{name}: speed-up", before_us / now_us, f"{name}: general path", Better.HIGHER)]
    Console().print(table)
    return figures


if __name__ == "__main__":
    main()
