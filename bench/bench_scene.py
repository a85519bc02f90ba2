"""Scene update time at 10, 50 and 200 objects: today's scene service against the one before issue 27.

One update = one radar frame carrying every object (front end, gating, global assignment, Kalman
updates, life cycle) plus one scene() build. "before" is services/scene as of BEFORE_REVISION (a filterpy
KalmanFilter per track, per-object front end and scene build), loaded from git beside today's code
(bench/scene_before.py) and fed the same frames in the same run; without git that column is left empty.
The scenes run turn about, frame by frame, so a load that comes and goes on the machine weighs on both alike, in
three rounds whose speed-ups give its interval (the best round of each is kept);
"alone ms" is today's scene by itself, the figure the 4 ms the issue asks stands against (the old scene's
objects, run in between, cost ours a tenth to a fifth: the two share the caches and the garbage collector).
Assoc ms: one frame's association alone, ours (only the gated pairs costed and solved) against every
measurement-track pair's cost by the pair-by-pair loop with a general inverse (association.polar_cost_loop) and
one assignment. The last column is how the update time grows from 50 to 200 objects against n log n's growth (at
most 1 is what the scene issue asks), today's scene alone, the two sizes turn about. Seeded; run with:

    .venv/bin/python -m bench.bench_scene
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from types import ModuleType

import numpy as np

from bench import scene_before
from bench.figure import Better, Figure, Unit, instruction_ratio, ratio
from bench.instructions_per_call import Workload, per_call
from bench.sizes import sized
from bench.turn_about import turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.services.scene import fusion as fusion_now
from coopdrive.services.scene.association import assign, likelihood_cost, polar_cost_loop
from coopdrive.services.scene.config import TrackingConfig
from coopdrive.services.scene.frame_association import associate
from coopdrive.v1 import ego_pb2, sensors_pb2

# main just before issue 27 (scene update at 200 objects in at most 4 ms).
BEFORE_REVISION = "d65fb12e6b01c721207f56ede5a9482dda679d1d"

SEED = 20160528
FRAME_S = 0.05
WARMUP_FRAMES = sized(10, 1)
TIMED_FRAMES = sized(40, 2)
EGO_SPEED_MPS = 20.0
RANGE_NOISE_M = 0.2
BEARING_NOISE_RAD = 0.003
# The quick size leaves out 200 objects: the brute-force association alone takes seconds there.
OBJECT_COUNTS = sized((10, 50, 200), (10, 50))
BRUTE_FORCE_REPEATS = sized(3, 1)
# Frames of our association per turn: 100 make a turn of some 60 ms, where 20 (12 ms) left the 200-object ratio to
# a single preemption.
ASSOCIATION_FRAMES = sized(100, 5)
# Turns of ours and the brute force (bench/turn_about.py).
ASSOCIATION_ROUNDS = sized(3, 1)
# Rounds of the frame-by-frame race of today's scene and the one before: their speed-up's interval.
SPEED_UP_ROUNDS = sized(3, 1)
# Turns of today's scene alone at the two largest counts, for the growth ratio and its interval.
GROWTH_ROUNDS = sized(3, 1)
# Frames of our association whose instructions are counted, and at which sizes: the brute force at 200 objects
# executes 5.5 billion instructions, 10 minutes under callgrind on this machine.
INSTRUCTION_FRAMES = 5
INSTRUCTION_OBJECT_COUNTS = (10, 50)
INSTRUCTION_WORKLOADS = "bench.bench_scene:instruction_workloads"


def layout(count: int, rng: np.random.Generator) -> np.ndarray:
    """Objects on a grid of 4 m lanes and 12 m rows ahead, each with its own speed: (x, y, speed)."""
    lanes = 9
    rows = math.ceil(count / lanes)
    out = []
    for k in range(count):
        row, lane = divmod(k, lanes)
        out.append((15.0 + 12.0 * row, 4.0 * (lane - lanes // 2), EGO_SPEED_MPS + rng.uniform(-1.0, 1.0)))
    assert rows * lanes >= count
    return np.array(out)


def frames(objects: np.ndarray, rng: np.random.Generator, count: int):
    for k in range(count):
        t = k * FRAME_S
        ego = ego_pb2.EgoState(x_m=EGO_SPEED_MPS * t, speed_mps=EGO_SPEED_MPS)
        ego.header.sample_time_s = t
        radar = sensors_pb2.RadarTracks()
        radar.header.sample_time_s = t
        for index, (x0, y, speed) in enumerate(objects, start=1):
            dx = x0 + speed * t - EGO_SPEED_MPS * t
            rng_m = math.hypot(dx, y)
            radar.tracks.add(track_id=index, range_m=rng_m + rng.normal(0.0, RANGE_NOISE_M),
                             azimuth_rad=math.atan2(y, dx) + rng.normal(0.0, BEARING_NOISE_RAD),
                             range_rate_mps=(speed - EGO_SPEED_MPS) * dx / rng_m, width_m=1.8)
        yield t, ego, radar


def run(fusion_modules: list[ModuleType], count: int) -> tuple[list[float], int]:
    """Median ms of one update with count objects for each fusion module, and how many objects the first one's last
    scene published. The modules take turns frame by frame, so a load that comes and goes on the machine weighs
    on both alike."""
    rng = np.random.default_rng(SEED)
    objects = layout(count, rng)
    fusions = [module.SceneFusion() for module in fusion_modules]
    for fusion in fusions:
        # A radar that sees everything: the field of view is not what is being measured here.
        fusion.config.radar.half_fov_rad = math.pi
    timings: list[list[float]] = [[] for _ in fusions]
    published = 0
    for k, (t, ego, radar) in enumerate(frames(objects, rng, WARMUP_FRAMES + TIMED_FRAMES)):
        for index, fusion in enumerate(fusions):
            start = time.process_time()
            fusion.on_radar(radar, ego)
            scene = fusion.scene(t)
            if k >= WARMUP_FRAMES:
                timings[index].append(time.process_time() - start)
            if index == 0:
                published = len(scene.objects)
    return [1e3 * float(np.median(timing)) for timing in timings], published


def association_calls(count: int, brute_force: bool = False, repeats: int = 20) -> list[Callable[[], object]]:
    """`repeats` frames' association of count measurements with count tracks, one call each: ours (association of
    the gated pairs, frame_association.associate), or every pair's cost by the pair-by-pair loop and one
    assignment. The measurements' noise is drawn here, before any call."""
    rng = np.random.default_rng(SEED)
    xy = layout(count, rng)[:, :2]
    cov = np.repeat(np.eye(2)[None] * 0.1, count, axis=0)
    origins = np.zeros_like(xy)
    tracking = TrackingConfig()

    def brute(meas_xy: np.ndarray) -> None:
        d2, log_det = polar_cost_loop(meas_xy, cov, origins, xy, cov, tracking.angle_emphasis, with_log_det=True)
        assign(likelihood_cost(d2, log_det), tracking.gate_chi2, gate_cost=d2)

    def ours(meas_xy: np.ndarray) -> None:
        associate(meas_xy, cov, origins, xy, cov, tracking)
    associate_one = brute if brute_force else ours
    return [lambda m=xy + rng.normal(0.0, 0.2, xy.shape): associate_one(m) for _ in range(repeats)]


def association_ms(count: int, brute_force: bool = False, repeats: int = 20) -> float:
    """Mean ms of this process's CPU per frame's association (association_calls)."""
    calls = association_calls(count, brute_force, repeats)
    start = time.process_time()
    for call in calls:
        call()
    return 1e3 * (time.process_time() - start) / repeats


def instruction_workloads() -> list[Workload]:
    """Ours and the brute force at each counted size, for bench/instructions_per_call.py; the brute force runs one
    frame, cold."""
    workloads = []
    for count in INSTRUCTION_OBJECT_COUNTS:
        workloads += [Workload(f"{count} objects: association", association_calls(count, repeats=INSTRUCTION_FRAMES)),
                      Workload(f"{count} objects: brute-force association",
                               association_calls(count, brute_force=True, repeats=1), warm=False)]
    return workloads


def association_ratios(count: int, by_time: float, instructions: dict[str, float] | None,
                       spread: float | None = None) -> list[Figure]:
    """Our association over the brute force's, in time and, where counted, in instructions (which guard it); the
    time ratio's `spread` from its turns (bench/turn_spread.py)."""
    name, baseline = f"{count} objects: association to brute force", f"{count} objects: brute-force association"
    counted = None if instructions is None or count not in INSTRUCTION_OBJECT_COUNTS else instruction_ratio(
        name, instructions[f"{count} objects: association"] / instructions[baseline], baseline)
    return ([] if counted is None else [counted]) + [
        ratio(name, by_time, baseline, Better.LOWER, spread=spread,
              guarded_by=None if counted is None else counted.name)]


def growth_to_n_log_n(fewer: int, count: int) -> Figure:
    """How today's scene update, alone, grows from `fewer` to `count` objects over n log n's growth; the two sizes
    run turn about in GROWTH_ROUNDS rounds, which give the ratio's interval (bench/turn_spread.py)."""
    fewer_ms, count_ms = turns([lambda: run([fusion_now], fewer)[0][0], lambda: run([fusion_now], count)[0][0]],
                               GROWTH_ROUNDS)
    n_log_n = (count * math.log(count)) / (fewer * math.log(fewer))
    return ratio(f"update growth {fewer} -> {count} objects to n log n's", min(count_ms) / min(fewer_ms) / n_log_n,
                 f"n log n's growth from {fewer} to {count}", Better.LOWER,
                 spread=turn_ratio_spread(count_ms, [n_log_n * ms for ms in fewer_ms]))


def main() -> list[Figure]:
    instructions = per_call(INSTRUCTION_WORKLOADS)
    before = scene_before.load(BEFORE_REVISION)
    print(f"scene update = radar frame with every object + scene(); median of {TIMED_FRAMES} frames, seed {SEED}; "
          f"before = services/scene at {BEFORE_REVISION[:12]}" + ("" if before else " (not available: no git)"))
    print(f"{'objects':>8} {'published':>9} {'before ms':>10} {'now ms':>8} {'speed-up':>9} {'alone ms':>9} "
          f"{'assoc ms':>9} {'brute-force assoc ms':>21} {'growth / n log n':>17}")
    now_ms, figures = {}, []
    for count in OBJECT_COUNTS:
        rounds = [run([fusion_now] + ([before] if before else []), count) for _ in range(SPEED_UP_ROUNDS)]
        published = rounds[-1][1]
        now_turns = [timings_ms[0] for timings_ms, _ in rounds]
        before_turns = [timings_ms[1] for timings_ms, _ in rounds] if before else [math.nan]
        now_ms[count], before_ms = min(now_turns), min(before_turns)
        (alone_ms,), _ = run([fusion_now], count)
        assoc_turns, brute_force_turns = turns(
            [lambda: association_ms(count, repeats=ASSOCIATION_FRAMES),
             lambda: association_ms(count, brute_force=True, repeats=BRUTE_FORCE_REPEATS)], ASSOCIATION_ROUNDS)
        assoc_ms, brute_force_ms = min(assoc_turns), min(brute_force_turns)
        growth = ""
        if count == OBJECT_COUNTS[-1]:
            growth_ratio = growth_to_n_log_n(OBJECT_COUNTS[-2], count)
            growth = f"{growth_ratio.value:.2f}"
            figures.append(growth_ratio)
        print(f"{count:>8} {published:>9} {before_ms:>10.2f} {now_ms[count]:>8.2f} {before_ms / now_ms[count]:>9.1f} "
              f"{alone_ms:>9.2f} {assoc_ms:>9.3f} {brute_force_ms:>21.2f} {growth:>17}")
        figures += [Figure(f"{count} objects: update, turn about", now_ms[count], Unit.MS),
                    Figure(f"{count} objects: update alone", alone_ms, Unit.MS),
                    Figure(f"{count} objects: association", assoc_ms, Unit.MS)] + association_ratios(
            count, assoc_ms / brute_force_ms, instructions, turn_ratio_spread(assoc_turns, brute_force_turns))
        if before:  # without git the scene before is not there to measure
            figures.append(ratio(f"{count} objects: speed-up over before", before_ms / now_ms[count],
                                 f"{count} objects: update before", Better.HIGHER,
                                 spread=turn_ratio_spread(before_turns, now_turns)))
    return figures


if __name__ == "__main__":
    main()
