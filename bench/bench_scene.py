"""Scene update time at 10, 50 and 200 objects, against a brute-force association baseline.

One update = one radar frame carrying every object (front end, gating, global assignment, Kalman
updates, life cycle) plus one scene() build. The baseline is the same pipeline with the gating cost
computed pair by pair in Python with a general matrix inverse (association.polar_cost_loop) instead
of the vectorised closed-form 2x2 version. Gating ms: the gate groups and their costs (ours) against
every measurement-track pair's cost by the loop (baseline). The last column is how the update time grows
from 50 to 200 objects against n log n's growth (at most 1 is what the scene issue asks). Seeded; run with:

    .venv/bin/python bench/bench_scene.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from coopdrive.services.scene.association import gate_groups, polar_cost_loop, polar_cost_matrix, polar_cost_pairs
from coopdrive.services.scene.fusion import SceneFusion
from coopdrive.services.scene.tracker import Tracker
from coopdrive.v1 import ego_pb2, sensors_pb2

SEED = 20160528
FRAME_S = 0.05
WARMUP_FRAMES = 10
TIMED_FRAMES = 40
# The baseline is slow enough at 200 objects that fewer frames give the same median.
BASELINE_TIMED_FRAMES = 10
EGO_SPEED_MPS = 20.0
RANGE_NOISE_M = 0.2
GATE_CHI2 = 9.21
BEARING_NOISE_RAD = 0.003


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


def run(count: int, cost_fn, timed_frames: int = TIMED_FRAMES) -> tuple[float, int]:
    rng = np.random.default_rng(SEED)
    objects = layout(count, rng)
    fusion = SceneFusion()
    pair_cost_fn = None if cost_fn is polar_cost_loop else polar_cost_pairs
    fusion.tracker = Tracker(fusion.config, cost_fn=cost_fn, pair_cost_fn=pair_cost_fn)
    # A radar that sees everything: the field of view is not what is being measured here.
    fusion.config.radar.half_fov_rad = math.pi
    timings = []
    scene = None
    for k, (t, ego, radar) in enumerate(frames(objects, rng, WARMUP_FRAMES + timed_frames)):
        start = time.perf_counter()
        fusion.on_radar(radar, ego)
        scene = fusion.scene(t)
        if k >= WARMUP_FRAMES:
            timings.append(time.perf_counter() - start)
    return 1e3 * float(np.median(timings)), len(scene.objects)


def association_only(count: int, cost_fn, repeats: int = 20, grouped: bool = False) -> float:
    rng = np.random.default_rng(SEED)
    xy = layout(count, rng)[:, :2]
    cov = np.repeat(np.eye(2)[None] * 0.1, count, axis=0)
    origins = np.zeros_like(xy)
    start = time.perf_counter()
    for _ in range(repeats):
        meas_xy = xy + rng.normal(0.0, 0.2, xy.shape)
        if not grouped:
            cost_fn(meas_xy, cov, origins, xy, cov, 1.2)
            continue
        for group_meas, group_tracks in gate_groups(meas_xy, cov, xy, cov, GATE_CHI2):
            cost_fn(meas_xy[group_meas], cov[group_meas], origins[group_meas], xy[group_tracks], cov[group_tracks], 1.2)
    return 1e3 * (time.perf_counter() - start) / repeats


def main() -> None:
    print(f"scene update = radar frame with every object + scene(); median of {TIMED_FRAMES} frames ({BASELINE_TIMED_FRAMES} for the baseline), seed {SEED}")
    print(f"{'objects':>8} {'published':>9} {'update ms':>10} {'baseline ms':>12} {'gating ms':>10} "
          f"{'baseline gating ms':>19} {'growth / n log n':>17}")
    update_ms = {}
    for count in (10, 50, 200):
        fast_ms, published = run(count, polar_cost_matrix)
        update_ms[count] = fast_ms
        slow_ms, _ = run(count, polar_cost_loop, BASELINE_TIMED_FRAMES)
        gate_fast = association_only(count, polar_cost_matrix, grouped=True)
        gate_slow = association_only(count, polar_cost_loop, repeats=3)
        growth = ""
        if count == 200:
            n_log_n = (200 * math.log(200)) / (50 * math.log(50))
            growth = f"{update_ms[200] / update_ms[50] / n_log_n:.2f}"
        print(f"{count:>8} {published:>9} {fast_ms:>10.2f} {slow_ms:>12.2f} {gate_fast:>10.3f} {gate_slow:>19.2f} "
              f"{growth:>17}")


if __name__ == "__main__":
    main()
