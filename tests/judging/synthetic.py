"""Hand-built runs written as MCAP recordings, for scoring tests."""

from __future__ import annotations

import math
from pathlib import Path

from coopdrive.recording.writer import McapRecorder
from coopdrive.v1 import ego_pb2, scene_pb2, sim_pb2

STEP_S = 0.1
LENGTH_M = 5.0
# The judge's footprint puts the rear axle 20 % of the length ahead of the rear bumper.
REAR_OVERHANG_M = 0.2 * LENGTH_M


def truth_at(time_s: float, vehicles: list[dict]) -> sim_pb2.GroundTruth:
    truth = sim_pb2.GroundTruth()
    truth.header.sample_time_s = time_s
    truth.header.sent_time_s = time_s
    for vehicle in vehicles:
        truth.vehicles.add(length_m=LENGTH_M, width_m=1.8, station_m=vehicle["x_m"], **vehicle)
    return truth


def two_car_frames(steps: int = 10) -> list[tuple[float, list[dict]]]:
    """Leader at x = 30 + 10 t, 10 m/s; automated follower at x = 12 t, 12 m/s, accel = t, 0.1 m off centre."""
    frames = []
    for k in range(steps + 1):
        t = k * STEP_S
        frames.append((t, [
            dict(vehicle_id="leader", x_m=30 + 10 * t, y_m=0.0, speed_mps=10.0, accel_mps2=0.0),
            dict(vehicle_id="follower", x_m=12 * t, y_m=0.0, speed_mps=12.0, accel_mps2=t, lateral_offset_m=0.1,
                 automated=True),
        ]))
    return frames


def write_two_car_recording(path: Path, switch_at_s: float = 0.5) -> Path:
    """Truth, the follower's ego state 0.5 m off (0.3 east, 0.4 north), and its scene of the leader whose object
    id changes from 7 to 9 at switch_at_s, beside a clutter object far away."""
    recorder = McapRecorder(path)
    for t, vehicles in two_car_frames():
        recorder.write("coopdrive/world/ground_truth", truth_at(t, vehicles))
    for k in range(10):
        t = (k + 0.5) * STEP_S
        state = ego_pb2.EgoState(x_m=12 * t + 0.3, y_m=0.4)
        state.header.sample_time_s = state.header.sent_time_s = t
        recorder.write("coopdrive/follower/ego/state", state)
        scene = scene_pb2.Scene()
        scene.header.sample_time_s = scene.header.sent_time_s = t
        leader = scene.objects.add(object_id=7 if t < switch_at_s else 9)
        leader.position.x_m, leader.position.y_m = 30 + 10 * t - REAR_OVERHANG_M, 0.0
        clutter = scene.objects.add(object_id=3)
        clutter.position.x_m, clutter.position.y_m = 200.0, 20.0
        recorder.write("coopdrive/follower/scene", scene)
    recorder.close()
    return path


def sinusoid_chain_frames(amplitudes_mps: list[float], frequency_hz: float, duration_s: float = 20.0,
                          mean_speed_mps: float = 20.0, spacing_m: float = 40.0) -> list[tuple[float, list[dict]]]:
    """Vehicles one behind the other (the first leads), speed = mean + A_i sin(2 pi f t)."""
    frames = []
    omega = 2 * math.pi * frequency_hz
    for k in range(int(round(duration_s / STEP_S)) + 1):
        t = k * STEP_S
        vehicles = []
        for index, amplitude in enumerate(amplitudes_mps):
            x = -index * spacing_m + mean_speed_mps * t + amplitude * (1 - math.cos(omega * t)) / omega
            vehicles.append(dict(vehicle_id=f"v{index}", x_m=x, y_m=0.0,
                                 speed_mps=mean_speed_mps + amplitude * math.sin(omega * t),
                                 accel_mps2=amplitude * omega * math.cos(omega * t), automated=index > 0))
        frames.append((t, vehicles))
    return frames
