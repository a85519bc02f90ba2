"""Judging traffic at signalised intersections from ground truth, as a road authority would.

Every figure comes from the truth alone (the vehicles, and each approach's stop line and signal state:
sim_pb2.SignalTruth), so a recording is judged the same as the run. A crossing is a vehicle's front bumper passing an
approach's stop line while it drives along that approach (within half a lane of its centre, within 45 degrees of
its direction); its instant is interpolated between the two truth samples around it.

- red-light violation: a crossing while the group shows red or red-amber (both forbid passing the stop line,
  Vienna Convention on Road Signs and Signals, art. 23), or after the amber seen before it ended;
- stops: falls of the speed below STOPPED_MPS from above MOVING_MPS on the approach's last APPROACH_M;
- time lost: the HCM's control delay, the time taken from APPROACH_M before the stop line to BEYOND_LINE_M past
  it less the time at free flow, the speed at which the vehicle entered that stretch (a crossing whose stretch the
  truth does not hold whole is left out of it);
- positive acceleration: the sum of the speed's increases over the same stretch (the integral of a+ dt, m/s), a
  proxy of the energy spent that braking does not give back;
- amber margin: for crossings not on red, how long before the group's red began (the end of its amber) the vehicle
  crossed; its minimum over the run shows how close to red the vehicles entered.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Collection, Sequence

import numpy as np

from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.v1 import infrastructure_pb2, sim_pb2

APPROACH_M = 200.0
BEYOND_LINE_M = 50.0
STOPPED_MPS = 0.5
MOVING_MPS = 3.0
HEADING_GATE_RAD = math.radians(45.0)
_STOP_STATES = (infrastructure_pb2.MOVEMENT_PHASE_STATE_STOP_AND_REMAIN,
                infrastructure_pb2.MOVEMENT_PHASE_STATE_PRE_MOVEMENT)

SignalFrames = Sequence[tuple[float, Sequence[sim_pb2.VehicleTruth], Sequence[sim_pb2.SignalTruth]]]


@dataclass(frozen=True)
class Crossing:
    vehicle_id: str
    intersection_id: int
    signal_group: int
    time_s: float
    red: bool
    # The end of amber less the crossing's instant; None for a crossing on red.
    amber_margin_s: float | None
    stops: int
    time_lost_s: float | None
    positive_accel_mps: float | None


def along_m(vehicle: sim_pb2.VehicleTruth, line: sim_pb2.SignalTruth) -> float | None:
    """How far the front bumper is past the stop line along its approach (negative before it); None off it."""
    front_m = vehicle.length_m - rear_overhang_m(vehicle.length_m)
    dx = vehicle.x_m + front_m * math.cos(vehicle.heading_rad) - line.stop_x_m
    dy = vehicle.y_m + front_m * math.sin(vehicle.heading_rad) - line.stop_y_m
    cos_h, sin_h = math.cos(line.heading_rad), math.sin(line.heading_rad)
    if abs(-dx * sin_h + dy * cos_h) > 0.5 * line.lane_width_m:
        return None
    if abs(math.remainder(vehicle.heading_rad - line.heading_rad, math.tau)) > HEADING_GATE_RAD:
        return None
    return dx * cos_h + dy * sin_h


def _approach_key(line: sim_pb2.SignalTruth) -> tuple:
    return line.intersection_id, line.signal_group, round(line.stop_x_m, 2), round(line.stop_y_m, 2)


def crossings(frames: SignalFrames) -> list[Crossing]:
    """Every crossing of every vehicle at every approach, in time order."""
    tracks: dict[tuple, list[tuple[float, float, float, sim_pb2.SignalTruth]]] = {}
    for time_s, vehicles, signals in frames:
        for line in signals:
            for vehicle in vehicles:
                along = along_m(vehicle, line)
                if along is not None:
                    tracks.setdefault((vehicle.vehicle_id, *_approach_key(line)), []).append(
                        (time_s, along, vehicle.speed_mps, line))
    found = []
    for key, track in tracks.items():
        for index in range(1, len(track)):
            (t0, a0, _, line), (t1, a1, _, _) = track[index - 1], track[index]
            if a0 < 0.0 <= a1:
                found.append(_crossing(key[0], track, index, t0 + (t1 - t0) * (-a0) / (a1 - a0), line))
    return sorted(found, key=lambda c: c.time_s)


def _crossing(vehicle_id: str, track: list, index: int, time_s: float, seen: sim_pb2.SignalTruth) -> Crossing:
    """seen: the approach's state at the last sample before the stop line."""
    if seen.state == infrastructure_pb2.MOVEMENT_PHASE_STATE_PRE_MOVEMENT:
        red = time_s < seen.phase_end_s
    else:
        red = seen.state in _STOP_STATES or time_s > seen.amber_end_s
    times = np.array([t for t, _, _, _ in track])
    along = np.array([a for _, a, _, _ in track])
    speeds = np.array([v for _, _, v, _ in track])
    # The stretch of this crossing: the samples around it on the same pass (along never falls on it).
    start = index - 1
    while start > 0 and along[start - 1] <= along[start] and along[start - 1] >= -APPROACH_M:
        start -= 1
    end = index
    while end + 1 < len(track) and along[end + 1] >= along[end] and along[end] <= BEYOND_LINE_M:
        end += 1
    stops = _stops(speeds[start:index])
    lost_s = accel_mps = None
    whole = start > 0 and along[start - 1] < -APPROACH_M and along[end] >= BEYOND_LINE_M and speeds[start] > STOPPED_MPS
    if whole:
        t_in = float(np.interp(-APPROACH_M, along[start - 1:end + 1], times[start - 1:end + 1]))
        t_out = float(np.interp(BEYOND_LINE_M, along[start:end + 1], times[start:end + 1]))
        lost_s = (t_out - t_in) - (APPROACH_M + BEYOND_LINE_M) / speeds[start]
        accel_mps = float(np.sum(np.clip(np.diff(speeds[start:end + 1]), 0.0, None)))
    return Crossing(vehicle_id, seen.intersection_id, seen.signal_group, time_s, red,
                    None if red else seen.amber_end_s - time_s, stops, lost_s, accel_mps)


def _stops(speeds: np.ndarray) -> int:
    """Falls below STOPPED_MPS, each after the speed was above MOVING_MPS since the last (a car creeping up in a
    queue stops once)."""
    count, moving = 0, False
    for speed_mps in speeds:
        if speed_mps > MOVING_MPS:
            moving = True
        elif speed_mps < STOPPED_MPS and moving:
            count, moving = count + 1, False
    return count


def signal_metrics(frames: SignalFrames, stacks: Collection[str]) -> dict[str, float]:
    """The stacks' figures (signal_*), and the scripted traffic's red-light violations; nothing without signals."""
    if not any(signals for _, _, signals in frames):
        return {}
    every = crossings(frames)
    ours = [c for c in every if c.vehicle_id in stacks]
    metrics = {"signal_red_light_violations": float(sum(c.red for c in ours)),
               "signal_red_light_violations_scripted": float(sum(c.red for c in every if c.vehicle_id not in stacks)),
               "signal_crossings": float(len(ours))}
    if not ours:
        return metrics
    metrics["signal_stops_per_crossing"] = float(np.mean([c.stops for c in ours]))
    lost = [c.time_lost_s for c in ours if c.time_lost_s is not None]
    if lost:
        metrics["signal_time_lost_s"] = float(np.mean(lost))
        metrics["signal_positive_accel_mps"] = float(np.mean([c.positive_accel_mps for c in ours
                                                              if c.positive_accel_mps is not None]))
    margins = [c.amber_margin_s for c in ours if c.amber_margin_s is not None]
    if margins:
        metrics["signal_min_amber_margin_s"] = float(min(margins))
    return metrics
