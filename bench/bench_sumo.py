"""The simulator's own CPU per simulated second among SUMO's traffic, beside the same world without it: the
sumo-motorway world (four stacks behind a scripted lead car on the shipped motorway) with its SUMO traffic (libsumo in
the simulator's process, over a hundred vehicles from its first seconds, ours mirrored into SUMO every step) and with
its sumo_traffic taken out, stepped in memory as bench_sim steps the string world, in turns about. Everything the
simulator does per step counts (SUMO's step and its vehicles in the ground truth, every stack's sensors seeing them,
the judge); the stacks send no commands, so their drivers hold speed and lane.

    .venv/bin/python -m bench.bench_sumo            (make bench runs it too)
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import yaml
from rich.console import Console
from rich.table import Table

from bench.bench_sim import SimulatorAlone, cpu_ms_in_turns, over_the_run
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_spread import turn_ratio_spread
from coopdrive.services.sim.config import packaged_scenario_file
from coopdrive.services.sim.scenario_config import load_scenario

SCENARIO = "sumo-motorway"
STACKS = 4
# SUMO's vehicles of the scenario are all on the road from its third second: a quick size of one second still steps
# SUMO with its first ones.
DURATION_S = sized(10.0, 1.0)
# The timed turns begin once SUMO's vehicles are all on the road, so that each turn is like the others and their
# ratios give the figure's interval (bench/turn_spread.py).
WARMUP_S = sized(3.0, 0.0)
TURNS = sized(5, 1)


def without_traffic(folder: Path) -> str:
    """The scenario file without its sumo_traffic, its map held absolute (the copy is in another folder)."""
    source = packaged_scenario_file(SCENARIO)
    data = yaml.safe_load(Path(source).read_text(encoding="utf-8"))
    data.pop("sumo_traffic")
    data["map"] = load_scenario(source).map
    path = folder / f"{SCENARIO}-without-traffic.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return str(path)


def cpu_ms_per_simulated_s(folder: Path) -> tuple[list[list[float]], float]:
    """(with SUMO's traffic, without it) CPU ms per simulated second in each of TURNS turns about over DURATION_S, and
    how many SUMO vehicles drove in the world with it (one SUMO per process: only one world has it)."""
    simulated_s = WARMUP_S + DURATION_S
    simulators = [SimulatorAlone(STACKS, SCENARIO, duration_s=simulated_s),
                  SimulatorAlone(STACKS, SCENARIO, without_traffic(folder), duration_s=simulated_s)]
    try:
        spent_ms = cpu_ms_in_turns(simulators, DURATION_S, TURNS, WARMUP_S)
        return spent_ms, simulators[0].service.feed.sim.traffic_metrics()["sumo_vehicles"]
    finally:
        for simulator in simulators:
            simulator.close()


def main(argv: list[str] | None = None) -> list[Figure]:
    with tempfile.TemporaryDirectory() as folder:
        (with_turns_ms, without_turns_ms), vehicles = cpu_ms_per_simulated_s(Path(folder))
    with_ms, without_ms = over_the_run(with_turns_ms), over_the_run(without_turns_ms)
    table = Table(title=f"simulator alone, {SCENARIO}, {STACKS} stacks, {DURATION_S:.0f} s simulated, real world")
    for column in ("world", "SUMO vehicles", "CPU ms per simulated s"):
        table.add_column(column, justify="right")
    table.add_row("with SUMO's traffic", f"{vehicles:.0f}", f"{with_ms:.0f}")
    table.add_row("without", "0", f"{without_ms:.0f}")
    Console().print(table)
    with_name, without_name = "with SUMO's traffic: simulator CPU", "without SUMO's traffic: simulator CPU"
    return [Figure(with_name, with_ms, Unit.MS_PER_SIMULATED_S),
            Figure(without_name, without_ms, Unit.MS_PER_SIMULATED_S),
            ratio("SUMO's traffic: simulator CPU with it to without", with_ms / without_ms, without_name,
                  Better.LOWER, spread=turn_ratio_spread(with_turns_ms, without_turns_ms))]


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
