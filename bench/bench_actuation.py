"""Command-to-frame latency inside the Actuator: on_control_command + step (maps, supervision, CAN encode).

Run: .venv/bin/python -m bench.bench_actuation [iterations]
Prints p50 / p99 / max in microseconds for each stage, as a table.
"""

import math
import os
import statistics
import sys
import time

from bench.figure import Figure, Unit
from bench.sizes import sized
from coopdrive.can.codec import VehicleCanCodec, VehicleCommand
from coopdrive.services.actuation.actuator import Actuator
from coopdrive.services.actuation.config import STACK_UPSTREAM
from coopdrive.v1 import actuation_pb2, control_pb2, ego_pb2, vehicle_pb2

SERVICES = STACK_UPSTREAM
STEP_S = 0.01
NS_PER_US = 1000.0
DEFAULT_ITERATIONS = sized(5000, 50)


def percentile(values: list[float], fraction: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(fraction * len(ordered)))]


def engaged_actuator() -> Actuator:
    actuator = Actuator()
    feed_world(actuator, 0.0)
    actuator.on_control_command(control_pb2.ControlCommand(), 0.0)
    decision = actuator.on_mode_request(actuation_pb2.ModeRequest(mode=actuation_pb2.DRIVING_MODE_AUTONOMOUS), 0.0)
    assert decision.accepted, decision.unmet
    return actuator


def feed_world(actuator: Actuator, now_s: float) -> None:
    for name in SERVICES:
        actuator.on_service_liveness(name, True)
    actuator.on_ego_state(ego_pb2.EgoState(mode=ego_pb2.LOCALISATION_MODE_GNSS_PRECISE), now_s)
    actuator.on_v2x_health(True, now_s)
    angle_rad = actuator.last_command.steering_angle_request_rad if actuator.last_command else 0.0
    actuator.on_vehicle_state(vehicle_pb2.VehicleCanState(gear=vehicle_pb2.GEAR_DRIVE, steering_angle_rad=angle_rad),
                              now_s)


def measure(iterations: int) -> dict[str, list[float]]:
    actuator = engaged_actuator()
    codec_tx, codec_rx = VehicleCanCodec(), VehicleCanCodec(check_counter=False)
    feedback = codec_tx.encode_vehicle_state(vehicle_pb2.VehicleCanState(gear=vehicle_pb2.GEAR_DRIVE))
    samples: dict[str, list[float]] = {"command -> frames (total)": [], "on_control_command": [],
                                       "step (incl. encode)": [], "encode 3 ACT_ frames": [],
                                       "decode 3 VEH_ frames": []}
    for i in range(1, iterations + 1):
        now_s = i * STEP_S
        feed_world(actuator, now_s)
        cmd = control_pb2.ControlCommand(accel_request_mps2=1.5 * math.sin(i / 50.0),
                                         steering_angle_request_rad=0.05 * math.sin(i / 80.0))
        t0 = time.perf_counter_ns()
        actuator.on_control_command(cmd, now_s)
        t1 = time.perf_counter_ns()
        frames, _ = actuator.step(now_s)
        t2 = time.perf_counter_ns()
        assert len(frames) >= 2 and actuator.mode == actuation_pb2.DRIVING_MODE_AUTONOMOUS
        codec_tx.encode_vehicle_command(VehicleCommand(throttle_ratio=0.2))
        t3 = time.perf_counter_ns()
        for msg in feedback:
            codec_rx.decode_vehicle_state(msg)
        t4 = time.perf_counter_ns()
        samples["command -> frames (total)"].append((t2 - t0) / NS_PER_US)
        samples["on_control_command"].append((t1 - t0) / NS_PER_US)
        samples["step (incl. encode)"].append((t2 - t1) / NS_PER_US)
        samples["encode 3 ACT_ frames"].append((t3 - t2) / NS_PER_US)
        samples["decode 3 VEH_ frames"].append((t4 - t3) / NS_PER_US)
    return samples


def main() -> list[Figure]:
    # An environment variable, not argv: `python -m bench NAME` passes the benchmark's name on argv.
    iterations = int(os.environ.get("BENCH_ACTUATION_CYCLES", DEFAULT_ITERATIONS))
    samples = measure(iterations)
    print(f"Actuator latency, {iterations} cycles, Python {sys.version.split()[0]}")
    print(f"{'stage':<28} {'p50 us':>9} {'p99 us':>9} {'max us':>9} {'mean us':>9}")
    figures = []
    for stage, values in samples.items():
        p50, p99 = percentile(values, 0.5), percentile(values, 0.99)
        print(f"{stage:<28} {p50:9.1f} {p99:9.1f} {max(values):9.1f} {statistics.fmean(values):9.1f}")
        figures += [Figure(f"{stage} p50", p50, Unit.US), Figure(f"{stage} p99", p99, Unit.US)]
    return figures


if __name__ == "__main__":
    main()
