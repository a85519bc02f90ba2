"""Control step time: our CACC against Ploeg's, alone and inside the LongitudinalController, plus lateral laws.

Run: .venv/bin/python -m bench.bench_control [iterations]
Prints p50 / p99 / max in microseconds per call, as a table. The control period is 20 ms (50 Hz).
"""

import os
import statistics
import time

from bench.figure import Figure, Unit
from bench.sizes import sized
from coopdrive.services.control.lateral import LateralController, LateralLaw
from coopdrive.services.control.longitudinal import CaccLaw, LongitudinalController, Spacing, Target
from coopdrive.services.control.longitudinal.cacc import LagCompensatedCacc
from coopdrive.services.control.longitudinal.ploeg import PloegCacc
from coopdrive.services.control.longitudinal.types import FollowInput
from coopdrive.services.control.profiles import CAR

DT_S = 0.02
NS_PER_US = 1000.0
DEFAULT_ITERATIONS = sized(20000, 50)
FOLLOW = FollowInput(gap_m=17.0, ego_speed_mps=22.0, ego_accel_mps2=0.1, pred_speed_mps=22.3,
                     pred_accel_mps2=0.2, standstill_m=6.0, time_gap_s=0.5)


def percentile(values: list[float], fraction: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(fraction * len(ordered)))]


def timed(call, iterations: int) -> list[float]:
    samples = []
    for k in range(iterations):
        start = time.perf_counter_ns()
        call(k)
        samples.append((time.perf_counter_ns() - start) / NS_PER_US)
    return samples


def controller_call(law: CaccLaw, targets: int):
    ctrl = LongitudinalController(CAR, cacc_law=law)
    tgts = [Target(object_id=i + 1, gap_m=17.0 + 10 * i, speed_mps=22.3, accel_mps2=0.2, v2v_age_s=0.04)
            for i in range(targets)]
    spacing = Spacing(6.0, 0.5)
    return lambda k: ctrl.step(k * DT_S, 22.0, 0.1, tgts, 25.0, spacing)


def main() -> list[Figure]:
    # An environment variable, not argv: `python -m bench NAME` passes the benchmark's name on argv.
    iterations = int(os.environ.get("BENCH_CONTROL_ITERATIONS", DEFAULT_ITERATIONS))
    ours, ploeg = LagCompensatedCacc(CAR.cacc, CAR.engine_lag_s), PloegCacc(CAR.ploeg)
    lateral = {law: LateralController(CAR, law) for law in LateralLaw}
    rows = [
        ("law: our CACC", lambda k: ours.step(DT_S, FOLLOW)),
        ("law: Ploeg CACC", lambda k: ploeg.step(DT_S, FOLLOW)),
        ("controller, ours, 1 target", controller_call(CaccLaw.OURS, 1)),
        ("controller, Ploeg, 1 target", controller_call(CaccLaw.PLOEG, 1)),
        ("controller, ours, 3 targets", controller_call(CaccLaw.OURS, 3)),
        ("controller, Ploeg, 3 targets", controller_call(CaccLaw.PLOEG, 3)),
    ]
    for law, ctrl in lateral.items():
        rows.append((f"lateral: {law.value}", lambda k, c=ctrl: c.step(k * DT_S, 22.0, 0.2, 0.01, 0.001)))
    print(f"{'call':32s} {'p50 us':>9s} {'p99 us':>9s} {'max us':>9s} {'mean us':>9s}")
    figures = []
    for name, call in rows:
        timed(call, min(iterations, 500))  # warm-up
        samples = timed(call, iterations)
        p50, p99 = percentile(samples, 0.5), percentile(samples, 0.99)
        print(f"{name:32s} {p50:9.1f} {p99:9.1f} {max(samples):9.1f} {statistics.fmean(samples):9.1f}")
        figures += [Figure(f"{name} p50", p50, Unit.US), Figure(f"{name} p99", p99, Unit.US)]
    return figures


if __name__ == "__main__":
    main()
