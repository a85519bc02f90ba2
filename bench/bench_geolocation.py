"""Filter updates per second: the Geolocator at 100 Hz odometry + 20 Hz GNSS against filterpy's bare EKF.

    python -m bench.bench_geolocation [--seconds 30]

Rows: filterpy ExtendedKalmanFilter predict+update with a constant F (the floor any filterpy-based filter
pays); our GeolocationEkf alone (CTRA step + gated update); the Geolocator (odometry, replay history,
frames) with fixes on time and 100 ms late; estimate() with lane matching; RoadMap.match alone.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "geolocation"))
from geolocation_drive import GNSS_EVERY, ORIGIN, can_state, drive, gnss_fix  # noqa: E402

from bench.figure import Better, Figure, Unit, ratio  # noqa: E402
from bench.sizes import sized  # noqa: E402
from bench.turn_about import turns  # noqa: E402
from bench.turn_spread import turn_ratio_spread  # noqa: E402
from coopdrive.roadmap import RoadMap  # noqa: E402
from coopdrive.services.geolocation.config import GeolocatorConfig  # noqa: E402
from coopdrive.services.geolocation.ekf import GeolocationEkf  # noqa: E402
from coopdrive.services.geolocation.frames import LeverArm  # noqa: E402
from coopdrive.services.geolocation.geolocator import Geolocator  # noqa: E402
from coopdrive.services.geolocation.motion_models import SPEED, STATE_DIM  # noqa: E402

SPEED_MPS = 80.0 / 3.6
# Turns of the two bare filters; each turn runs its share of the drive's updates (bench/turn_about.py).
FILTER_ROUNDS = sized(5, 1)


def bare_filterpy(n_updates: int) -> float:
    """The same state size as ours, so that the matrices cost alike."""
    kf = ExtendedKalmanFilter(dim_x=STATE_DIM, dim_z=2)
    kf.x = np.zeros(STATE_DIM)
    kf.F = np.eye(STATE_DIM) + np.eye(STATE_DIM, k=1) * 0.01
    kf.Q = np.eye(STATE_DIM) * 1e-4
    H = np.zeros((2, STATE_DIM))
    H[0, 0] = H[1, 1] = 1.0
    R = np.eye(2) * 0.01
    z = np.array([0.1, 0.1])
    start = time.process_time()
    for _ in range(n_updates):
        kf.predict()
        kf.update(z, lambda x: H, lambda x: H @ x, R=R)
    return time.process_time() - start


def our_ekf(n_updates: int) -> float:
    ekf = GeolocationEkf()
    x0 = np.zeros(STATE_DIM)
    x0[SPEED] = SPEED_MPS
    ekf.initialise(0.0, x0, np.eye(STATE_DIM) * 0.01)
    start = time.process_time()
    for i in range(1, n_updates + 1):
        t = i * 0.01
        ekf.predict_to(t)
        if i % GNSS_EVERY == 0:
            ekf.update_gnss_position(SPEED_MPS * t, 0.0, 0.05, 0.05, LeverArm())
        else:
            ekf.update_odometry(SPEED_MPS, 0.0, 0.01, 0.01)
    return time.process_time() - start


def geolocator_run(seconds: float, fix_delay_s: float, estimate_hz: float, road_map: RoadMap | None
                   ) -> tuple[float, int]:
    """Wall time spent inside the Geolocator only (message building excluded) and the number of inputs."""
    truth = drive(seconds, SPEED_MPS, seconds / 3, 500.0)
    rng = np.random.default_rng(0)
    cans = [can_state(truth, i, rng, 0.01) for i in range(len(truth.time_s))]
    fixes = {i: gnss_fix(truth, i, rng, 0.05, 1.0)[0] for i in range(0, len(truth.time_s), GNSS_EVERY)}
    geolocator = Geolocator(GeolocatorConfig(antenna_x_m=1.0), road_map=road_map, origin=ORIGIN)
    delay_steps = round(fix_delay_s / 0.01)
    estimate_every = round(100 / estimate_hz) if estimate_hz else 0
    inputs = 0
    start = time.perf_counter()
    for i, t in enumerate(truth.time_s):
        geolocator.on_can_state(cans[i])
        inputs += 1
        fix = fixes.get(i - delay_steps)
        if fix is not None:
            geolocator.on_gnss_fix(fix)
            inputs += 1
        if estimate_every and i % estimate_every == 0:
            geolocator.estimate(t)
    return time.perf_counter() - start, inputs


def map_match(n_calls: int) -> float:
    road_map = RoadMap.load("a270")
    lane = road_map.lanes[0]
    points = [lane.pose_at(s, 0.5) for s in np.linspace(0.0, lane.length_m, n_calls)]
    start = time.perf_counter()
    for x, y, heading in points:
        road_map.match(x, y, heading)
    return time.perf_counter() - start


def main(argv: list[str] | None = None) -> list[Figure]:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=sized(30.0, 1.0), help="simulated drive length")
    args = parser.parse_args(argv or [])
    n = int(args.seconds * 100) // FILTER_ROUNDS
    # The two filters turn about, so that their ratio's sides share the machine's load alike.
    bare_turns_s, ours_turns_s = turns([lambda: bare_filterpy(n), lambda: our_ekf(n)], FILTER_ROUNDS)
    bare_s, ours_s = min(bare_turns_s), min(ours_turns_s)
    rows = [("filterpy EKF predict+update (bare)", n, bare_s), ("GeolocationEkf CTRA predict+gated update", n, ours_s)]
    elapsed, inputs = geolocator_run(args.seconds, 0.0, 0.0, None)
    rows.append(("Geolocator, fixes on time", inputs, elapsed))
    elapsed, inputs = geolocator_run(args.seconds, 0.1, 0.0, None)
    rows.append(("Geolocator, fixes 100 ms late (replay)", inputs, elapsed))
    elapsed, inputs = geolocator_run(args.seconds, 0.1, 50.0, RoadMap.load("a270"))
    rows.append(("  + estimate() at 50 Hz with lane match", inputs, elapsed))
    elapsed = map_match(2000)
    rows.append(("RoadMap.match on the a270 (calls)", 2000, elapsed))
    realtime_inputs_per_s = 100 + 100 / GNSS_EVERY
    print(f"{'case':44s} {'count':>7s} {'per s':>10s} {'us each':>9s} {'x real time':>11s}")
    figures = []
    for name, count, seconds in rows:
        rate = count / seconds
        realtime = f"{rate / realtime_inputs_per_s:11.1f}" if name.startswith(("Geolocator", "  +")) else " " * 11
        print(f"{name:44s} {count:7d} {rate:10.0f} {1e6 / rate:9.1f} {realtime}")
        figures.append(Figure(name.strip(), rate, Unit.PER_S))
    print(f"real time needs {realtime_inputs_per_s:.0f} inputs/s (100 Hz odometry + {100 / GNSS_EVERY:.0f} Hz GNSS)")
    (bare, bare_n, bare_s), (ours, ours_n, ours_s) = rows[0], rows[1]
    return figures + [ratio(f"{ours}: time x bare", (ours_s / ours_n) / (bare_s / bare_n), bare, Better.LOWER,
                            spread=turn_ratio_spread(ours_turns_s, bare_turns_s))]


if __name__ == "__main__":
    main(sys.argv[1:])
