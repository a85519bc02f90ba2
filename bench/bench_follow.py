"""The follow loop: real-time factor in lockstep, and sensor-sample-to-actuation-command latency.

Latency is measured on the wall clock at the run's hub: from the arrival of the simulator's
clock message that closes step k (its sensor samples went out just before it) to the arrival of
the actuation command computed in that step.

Before issue 27 (quiet 2-core machine, one process per service): real-time factor 4.2, sensor -> command p50
7.1 ms, p99 15.6 ms. The issue asks for 20 and a p99 of at most 5 ms. The row "a thread per service (before)" is
the default layout as it was before a vehicle's services shared one worker thread, measured in the same run.
"""

from __future__ import annotations

from statistics import fmean

import numpy as np
from rich.console import Console
from rich.table import Table

from bench import baselines
from bench.failure import require_success
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.step_latency import StepLatency
from bench.turn_about import turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.launch.run import RunOptions, run_scenario

DURATION_S = sized(60.0, 1.0)
# A realtime run waits for the wall clock, so its latency is that of a loop with time to spare, as on the car.
REALTIME_DURATION_S = sized(20.0, 1.0)
REQUIRED_REALTIME_FACTOR = 20.0
STEP_S = 0.02
# The ratio's two layouts: a vehicle's services on one worker thread, and each on its own as before. The ratio comes
# from RATIO_ROUNDS rounds of both, turn about, of RATIO_DURATION_S each, and gets its interval from them
# (bench/turn_spread.py): from one run of each, two quiet runs of one commit can differ by the machine alone.
NOW, BEFORE = "one per vehicle", "one per vehicle, a thread per service (before)"
RATIO_ROUNDS = sized(3, 1)
RATIO_DURATION_S = sized(20.0, 1.0)


def run(processes: ProcessLayout, realtime: bool = False, thread_per_service: bool = False,
        duration_s: float | None = None):
    """`thread_per_service`: a vehicle's group gives each service its own thread, as before the shared worker.
    `duration_s`: simulated seconds, by default DURATION_S (REALTIME_DURATION_S paced to the wall clock)."""
    latency = StepLatency()
    if duration_s is None:
        duration_s = REALTIME_DURATION_S if realtime else DURATION_S
    with baselines.thread_per_service(thread_per_service):
        result = run_scenario(RunOptions(duration_s=duration_s,
                                         realtime=realtime, observer=latency.observe,
                                         processes=processes))
    return result, latency


def percentiles(latencies_ms: np.ndarray) -> tuple[str, str]:
    """p50 and p99 in ms, or dashes when no step was measured."""
    if not latencies_ms.size:
        return "-", "-"
    return tuple(f"{np.percentile(latencies_ms, q):.2f}" for q in (50, 99))


def main() -> list[Figure]:
    table = Table(title=f"follow scenario, lockstep, {DURATION_S:.0f} s simulated, and {REALTIME_DURATION_S:.0f} s "
                        f"paced to the wall clock (required sim_time_s / wall_time_s >= {REQUIRED_REALTIME_FACTOR})")
    for column in ("processes", "success", "sim_time_s / wall_time_s", "steps per wall second",
                   "sensor -> command p50 (ms)", "p99 (ms)", "p50 / p99, steps with the scene's update",
                   "p50 / p99, the other steps"):
        table.add_column(column, justify="right")
    service, vehicle, one = ProcessLayout.SERVICE, ProcessLayout.VEHICLE, ProcessLayout.ONE
    layouts = (("one per service", service, False, False),
               (BEFORE, vehicle, False, True), (NOW, vehicle, False, False), ("one for the run", one, False, False),
               ("one per service, realtime", service, True, False), ("one per vehicle, realtime", vehicle, True, False),
               ("one for the run, realtime", one, True, False))
    # The quick size keeps the ratio's two layouts and one paced run: every path of this benchmark, in 3 runs of 7.
    layouts = sized(layouts, layouts[1:3] + layouts[-1:])
    figures, factors = [], {}
    for label, processes, realtime, thread_per_service in layouts:
        result, latency = run(processes, realtime, thread_per_service)
        require_success(result, f"the run {label!r}")
        p50, p99 = percentiles(latency.latencies_ms())
        factors[label] = result.sim_time_s / result.wall_time_s
        table.add_row(label, str(result.success), f"{factors[label]:.2f}",
                      f"{result.sim_time_s / STEP_S / result.wall_time_s:.0f}", p50, p99,
                      " / ".join(percentiles(latency.latencies_ms(scene_steps=True))),
                      " / ".join(percentiles(latency.latencies_ms(scene_steps=False))))
        if not realtime:  # a paced run's factor is 1 by design
            figures.append(Figure(f"{label}: real-time factor", factors[label], Unit.REALTIME_FACTOR))
        figures += [Figure(f"{label}: sensor -> command p{q}", _percentile(latency.latencies_ms(), q), Unit.MS)
                    for q in (50, 99)]
    Console().print(table)
    return figures + [shared_worker_to_threads()]


def shared_worker_to_threads() -> Figure:
    """NOW's real-time factor to BEFORE's, from RATIO_ROUNDS rounds of both, turn about."""
    def factor(thread_per_service: bool) -> float:
        result, _ = run(ProcessLayout.VEHICLE, thread_per_service=thread_per_service, duration_s=RATIO_DURATION_S)
        require_success(result, f"the {RATIO_DURATION_S:g} s run {BEFORE if thread_per_service else NOW!r}")
        return result.sim_time_s / result.wall_time_s
    now_turns, before_turns = turns([lambda: factor(False), lambda: factor(True)], RATIO_ROUNDS)
    print(f"{NOW} to a thread per service, {RATIO_ROUNDS} rounds of {RATIO_DURATION_S:g} s: real-time factors "
          f"{', '.join(f'{n:.1f}/{b:.1f}' for n, b in zip(now_turns, before_turns))}")
    return ratio(f"{NOW}: real-time factor to a thread per service", fmean(now_turns) / fmean(before_turns),
                 f"{BEFORE}: real-time factor", Better.HIGHER, spread=turn_ratio_spread(now_turns, before_turns))


def _percentile(latencies_ms: np.ndarray, q: int) -> float:
    """NaN when no step was measured: the runner then fails the benchmark naming the figure."""
    return float(np.percentile(latencies_ms, q)) if latencies_ms.size else float("nan")


if __name__ == "__main__":
    main()
