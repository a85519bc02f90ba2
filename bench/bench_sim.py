"""The simulator's own CPU per simulated second, without the stacks or the bus: the simulator service of a string
run with 1, 4 and 8 stack vehicles, stepped in memory (MemoryContext) as the clock master steps it. Everything
it does per step counts (vehicles, every stack's sensors, CAN frames, the scripted vehicles' CAMs, the radio
boxes' datagrams, ground truth, the judge) and each message is serialised as the bus would; the lockstep
barrier and Zenoh do not. The stacks send no commands, so their drivers hold speed and lane: the same sensors,
the same world. GNSS goes out as gnss/fix, not NMEA on a pty.

    .venv/bin/python -m bench.bench_sim            (make bench runs it too)
    .venv/bin/python -m bench.bench_sim --profile  (cProfile of the 8-stack case, top functions)
    .venv/bin/python -m bench.bench_sim --digest   (sha256 of every message of the 8-stack case: a change meant
                                                    to leave the model alone must leave it alone)

Issue 27's figure before the work (a whole 8-stack run, the simulator's process, 1,645 ms per simulated second) is
printed beside the table.
"""

from __future__ import annotations

import argparse
import cProfile
import hashlib
import pstats
import socket
import statistics
import time

from rich.console import Console
from rich.table import Table

from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_about import cpu_seconds
from bench.turn_spread import turn_ratio_spread
from coopdrive.launch.ports import free_udp_ports
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.sim.config import SimConfig
from coopdrive.services.sim.scenario_config import load_scenario
from coopdrive.services.sim.service import SimService

SCENARIO = "string"
STACK_COUNTS = (1, 4, 8)
DURATION_S = sized(10.0, 0.5)
TURNS = sized(10, 2)
TARGET_MS_PER_SIMULATED_S = 150.0
# Issue 27's figure before the work: the simulator's process in a whole 8-stack run (not the simulator alone).
BEFORE_ISSUE_MS_PER_SIMULATED_S = 1645.0


class SimulatorAlone:
    """The simulator service of a string run (or another scenario, by name or file) with `stacks` stack vehicles, in
    memory; each stack's radio box port has a socket that is never read (the kernel drops what overflows it, as a
    busy stack would not)."""

    def __init__(self, stacks: int, scenario: str = SCENARIO, scenario_file: str = "", duration_s: float = DURATION_S):
        config = SimConfig(scenario=scenario, scenario_file=scenario_file)
        scenario = load_scenario(config.scenario_path())
        stack_ids = [v.vehicle_id for v in scenario.vehicles if v.role.value == "stack"][:stacks]
        ports = iter(free_udp_ports(2 * len(stack_ids)))
        links = {vehicle_id: {"box_port": next(ports), "stack_port": next(ports)} for vehicle_id in stack_ids}
        self._stack_sockets = []
        for link in links.values():
            sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            sock.bind(("127.0.0.1", link["stack_port"]))
            self._stack_sockets.append(sock)
        self.config = config.model_copy(update={"stacks": stack_ids, "radio_links": links,
                                                "duration_s": duration_s + 1.0})
        self.ctx = MemoryContext("world", "sim")
        self.service = SimService(self.config, self.ctx)
        self.service.start()
        self.service.on_clock_started(time.monotonic())

    def steps_in(self, duration_s: float) -> int:
        return round(duration_s / self.config.step_s) + 1

    def run(self, first_step: int, end_step: int, digest=None) -> None:
        """Steps the simulator from first_step up to end_step; `digest` (a hashlib object), if given, takes every
        message."""
        for k in range(first_step, end_step):
            self.ctx.advance_to(k * self.config.step_s)
            for key, message in self.ctx.outputs:
                wire = message.SerializeToString()
                if digest is not None:
                    digest.update(key.encode())
                    digest.update(wire)
            self.ctx.outputs.clear()

    def close(self) -> None:
        self.service.stop()
        for sock in self._stack_sockets:
            sock.close()


def cpu_ms_per_simulated_s(stack_counts: tuple[int, ...]) -> list[list[float]]:
    """Each world's CPU ms per simulated second in each turn, the worlds stepping DURATION_S in TURNS turns about
    (a load that comes and goes weighs on all alike; one world after the other moved the 8-to-1 ratio by 21 %
    between two quiet runs of the same code)."""
    simulators = [SimulatorAlone(stacks) for stacks in stack_counts]
    try:
        return cpu_ms_in_turns(simulators, DURATION_S, TURNS)
    finally:
        for simulator in simulators:
            simulator.close()


def cpu_ms_in_turns(simulators: list[SimulatorAlone], duration_s: float, turns: int,
                    warmup_s: float = 0.0) -> list[list[float]]:
    """Each simulator's CPU ms per simulated second in each of `turns` turns about over duration_s: [simulator][turn].
    The turns step the same simulated seconds in every world, so each turn gives one ratio between worlds; a turn
    that steps a busier part of the scenario is busier in all of them. The first warmup_s are stepped untimed, so
    that a scenario whose traffic is still arriving does not make its first turn unlike the others."""
    warm_steps = simulators[0].steps_in(warmup_s) - 1 if warmup_s > 0 else 0
    for simulator in simulators:
        simulator.run(0, warm_steps)
    steps = simulators[0].steps_in(duration_s)
    step_s = duration_s / steps
    bounds = [warm_steps + round(turn * steps / turns) for turn in range(turns + 1)]
    spent_ms: list[list[float]] = [[] for _ in simulators]
    for first_step, end_step in zip(bounds, bounds[1:]):
        for index, simulator in enumerate(simulators):
            spent_s = cpu_seconds(lambda s=simulator: s.run(first_step, end_step))
            spent_ms[index].append(1000.0 * spent_s / ((end_step - first_step) * step_s))
    return spent_ms


def over_the_run(per_turn_ms: list[float]) -> float:
    """A world's CPU ms per simulated second over all its turns (they step equal shares of the run)."""
    return statistics.fmean(per_turn_ms)


def main(argv: list[str] | None = None) -> list[Figure] | None:
    parser = argparse.ArgumentParser(description="the simulator's CPU per simulated second")
    parser.add_argument("--profile", action="store_true", help="cProfile the 8-stack world instead")
    parser.add_argument("--digest", action="store_true", help="print the sha256 of the 8-stack world's messages")
    args = parser.parse_args(argv or [])
    if args.digest:
        simulator, digest = SimulatorAlone(max(STACK_COUNTS)), hashlib.sha256()
        simulator.run(0, simulator.steps_in(DURATION_S), digest)
        simulator.close()
        print(digest.hexdigest())
        return None
    if args.profile:
        simulator = SimulatorAlone(max(STACK_COUNTS))
        profiler = cProfile.Profile()
        profiler.runcall(simulator.run, 0, simulator.steps_in(DURATION_S))
        simulator.close()
        pstats.Stats(profiler).sort_stats("tottime").print_stats(35)
        return None
    table = Table(title=f"simulator alone, {SCENARIO}, {DURATION_S:.0f} s simulated, real world "
                        f"(target: below {TARGET_MS_PER_SIMULATED_S:.0f} ms per simulated s with 8 stacks)")
    for column in ("stacks", "CPU ms per simulated s", "per stack"):
        table.add_column(column, justify="right")
    figures, per_turn_ms = [], cpu_ms_per_simulated_s(STACK_COUNTS)
    for stacks, turns_ms in zip(STACK_COUNTS, per_turn_ms):
        cpu_ms = over_the_run(turns_ms)
        table.add_row(str(stacks), f"{cpu_ms:.0f}", f"{cpu_ms / stacks:.0f}")
        figures.append(Figure(f"{stacks} stacks: simulator CPU", cpu_ms, Unit.MS_PER_SIMULATED_S))
    console = Console()
    console.print(table)
    console.print(f"before issue 27: {BEFORE_ISSUE_MS_PER_SIMULATED_S:,.0f} ms per simulated s with 8 stacks, the "
                  f"simulator's process in a whole run; in a whole run now, see its worker_cpu_s (docs/performance.md)")
    fewest, most = STACK_COUNTS[0], STACK_COUNTS[-1]
    per_stack_ms = [turn_ms / most for turn_ms in per_turn_ms[-1]]
    return figures + [ratio(f"{most} stacks: CPU per stack to {fewest} stack's", figures[-1].value / most / figures[0].value,
                            f"{fewest} stacks: simulator CPU", Better.LOWER,
                            spread=turn_ratio_spread(per_stack_ms, per_turn_ms[0]))]


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
