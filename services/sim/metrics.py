"""Judging a run from ground truth: safety, comfort, tracking errors, string stability, localisation."""
from __future__ import annotations

import itertools
import math
from typing import Callable, Collection, Iterator, Mapping, Sequence

import numpy as np

from coopdrive.roadmap.build_maps import LANE_WIDTH_M
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim import geometry
from coopdrive.services.sim.signal_metrics import signal_metrics
from coopdrive.services.sim.string_gain import judged_string_gains
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import sim_pb2

KMH_PER_MPS = 3.6
DEFAULT_SAFETY_RADIUS_M = 7.5
# Paths cross when headings are more than 30 degrees from parallel (or antiparallel).
CROSSING_SIN = math.sin(math.radians(30.0))
# Time gaps are meaningless near standstill.
MIN_SPEED_FOR_TIME_GAP_MPS = 0.5
# Heudiasyc eq. (4) defaults: standstill distance r and time headway h.
DEFAULT_STANDSTILL_M = 6.0
DEFAULT_HEADWAY_S = 1.5
# Well beyond control's comfort deceleration (2 m/s2, services/control/profiles.py): a car brakes this hard only
# on its emergency path, or its driver's foot.
HARD_BRAKE_MPS2 = 3.0
# A hard brake is called for by a vehicle ahead in the lane or the next one that brakes beyond comfort as well, or
# that would be reached within this time at the speeds of the moment.
CALLED_FOR_DECEL_MPS2 = 2.0
CALLED_FOR_TIME_TO_COLLISION_S = 4.0
# A brake shows in the truth up to this long after it was asked for (actuation delay and driveline lag), so what
# called for it is looked for over this window before its onset.
BRAKE_BUILD_UP_S = 1.0
# A vehicle whose footprint reaches this near the judged vehicle's flank is in its own path; beyond it, out to a
# lane's width, only traffic going the same way counts (oncoming traffic in the next lane passes by).
PATH_MARGIN_M = 0.5


def _corners(v: sim_pb2.VehicleTruth) -> np.ndarray:
    return geometry.footprint_corners(v.x_m, v.y_m, v.heading_rad, v.length_m, v.width_m)


def _centre(v: sim_pb2.VehicleTruth) -> np.ndarray:
    return _corners(v).mean(axis=0)


def _judged(a: sim_pb2.VehicleTruth, b: sim_pb2.VehicleTruth, ours: Collection[str] | None) -> bool:
    """Whether a pair is ours to judge: any pair, or (ours given: the scenario's vehicles among SUMO's traffic) a pair
    with one of ours in it; two of SUMO's vehicles are SUMO's to judge (its own collision count)."""
    return ours is None or a.vehicle_id in ours or b.vehicle_id in ours


def _onsets(truth: TruthSeries, condition: Callable[[sim_pb2.VehicleTruth, sim_pb2.VehicleTruth], bool],
            ours: Collection[str] | None = None) -> int:
    """How many times a pair of vehicles starts to satisfy `condition` (a lasting contact counts once)."""
    active: set[tuple[str, str]] = set()
    count = 0
    for _, vehicles in truth.frames:
        now = {(a.vehicle_id, b.vehicle_id) for a, b in _judged_pairs(vehicles, ours) if condition(a, b)}
        count += len(now - active)
        active = now
    return count


def _judged_pairs(vehicles: Sequence[sim_pb2.VehicleTruth],
                  ours: Collection[str] | None) -> Iterator[tuple[sim_pb2.VehicleTruth, sim_pb2.VehicleTruth]]:
    """Each pair _judged, once, the one of smaller id first. Among SUMO's traffic only the pairs with one of ours:
    the judge's time grows with ours times all, not with the square of a hundred SUMO vehicles."""
    ordered = sorted(vehicles, key=lambda v: v.vehicle_id)
    if ours is None:
        yield from itertools.combinations(ordered, 2)
        return
    for a in ordered:
        if a.vehicle_id not in ours:
            continue
        for b in ordered:
            if b.vehicle_id == a.vehicle_id or (b.vehicle_id in ours and b.vehicle_id < a.vehicle_id):
                continue
            yield (a, b) if a.vehicle_id < b.vehicle_id else (b, a)


def _reach_m(v: sim_pb2.VehicleTruth) -> float:
    """The farthest any point of the footprint is from the vehicle's reference point (its rear axle)."""
    back_m = rear_overhang_m(v.length_m)
    return math.hypot(max(back_m, v.length_m - back_m), v.width_m / 2.0)


def _footprints_overlap(a: sim_pb2.VehicleTruth, b: sim_pb2.VehicleTruth) -> bool:
    # Footprints farther apart than their reaches cannot touch: most pairs of most frames are settled without
    # building corners (the same answer, a tenth of the judge's time in an 8-stack run).
    if math.hypot(a.x_m - b.x_m, a.y_m - b.y_m) > _reach_m(a) + _reach_m(b):
        return False
    return geometry.rectangles_overlap(_corners(a), _corners(b))


def collisions(truth: TruthSeries, ours: Collection[str] | None = None) -> int:
    return _onsets(truth, _footprints_overlap, ours)


def safety_circle_violations(truth: TruthSeries, radius_m: float = DEFAULT_SAFETY_RADIUS_M,
                             ours: Collection[str] | None = None) -> int:
    """Onsets of two vehicle centres closer than radius_m (the organisers' safety circle)."""
    return _onsets(truth, lambda a, b: float(np.hypot(*(_centre(a) - _centre(b)))) < radius_m, ours)


def crossing_circle_violations(truth: TruthSeries, radius_m: float = DEFAULT_SAFETY_RADIUS_M,
                               ours: Collection[str] | None = None) -> int:
    """Safety-circle onsets between vehicles whose paths cross (headings more than 30 degrees from parallel):
    at an intersection, unlike two cars passing in their own lanes or following each other."""
    def crossing_too_close(a: sim_pb2.VehicleTruth, b: sim_pb2.VehicleTruth) -> bool:
        crossing = abs(math.sin(a.heading_rad - b.heading_rad)) > CROSSING_SIN
        return crossing and float(np.hypot(*(_centre(a) - _centre(b)))) < radius_m
    return _onsets(truth, crossing_too_close, ours)


def bumper_gap_m(leader: sim_pb2.VehicleTruth, follower: sim_pb2.VehicleTruth) -> float:
    """Leader's rear bumper to follower's front bumper along the lane (stations are at the rear axles)."""
    leader_rear = leader.station_m - rear_overhang_m(leader.length_m)
    follower_front = follower.station_m + follower.length_m - rear_overhang_m(follower.length_m)
    return leader_rear - follower_front


Pair = tuple[sim_pb2.VehicleTruth, sim_pb2.VehicleTruth]


def side_by_side(a: sim_pb2.VehicleTruth, b: sim_pb2.VehicleTruth) -> bool:
    """Two vehicles matched to one lane whose widths do not overlap across it (a car moved aside for an
    emergency vehicle passing in the corridor): neither can run into the other from behind."""
    return abs(a.lateral_offset_m - b.lateral_offset_m) >= (a.width_m + b.width_m) / 2.0


def following_pairs(vehicles: Sequence[sim_pb2.VehicleTruth]) -> list[Pair]:
    """(leader, follower): each vehicle and the nearest one ahead in its lane that it could run into. Every
    road numbers its lanes from 0, and measures stations from its own start, so a lane is told apart by its road
    (a SUMO network's edges one after the other) and its direction too: cars on crossing or opposite roads, or on
    the approach to a junction and past it, never follow one another."""
    pairs = []
    by_lane: dict[tuple[str, int, int, int], list[sim_pb2.VehicleTruth]] = {}
    for vehicle in vehicles:
        direction = (round(math.cos(vehicle.heading_rad)), round(math.sin(vehicle.heading_rad)))
        by_lane.setdefault((vehicle.road_id, vehicle.lane_index, *direction), []).append(vehicle)
    for lane_vehicles in by_lane.values():
        ordered = sorted(lane_vehicles, key=lambda v: v.station_m, reverse=True)
        for index, follower in enumerate(ordered[1:], start=1):
            ahead = (v for v in reversed(ordered[:index]) if not side_by_side(v, follower))
            leader = next(ahead, None)
            if leader is not None:
                pairs.append((leader, follower))
    return pairs


def gaps(truth: TruthSeries, ours: Collection[str] | None = None) -> dict[str, float]:
    min_gap, min_time_gap = math.inf, math.inf
    for _, vehicles in truth.frames:
        for leader, follower in following_pairs(vehicles):
            if not _judged(leader, follower, ours):
                continue
            gap = bumper_gap_m(leader, follower)
            min_gap = min(min_gap, gap)
            if follower.speed_mps > MIN_SPEED_FOR_TIME_GAP_MPS:
                min_time_gap = min(min_time_gap, gap / follower.speed_mps)
    return {"min_gap_m": min_gap, "min_time_gap_s": min_time_gap}


def error_stats(errors: np.ndarray, key: str, unit: str) -> dict[str, float]:
    """An error series as the literature reports it: `{key}_{unit}` is the mean absolute error, beside the RMS,
    the 95th percentile and the largest absolute error; the signed mean is kept as `{key}_bias_{unit}` (with the
    standard deviation about it), since a signed mean alone lets errors of both signs cancel."""
    errors = np.asarray(errors, dtype=float)
    errors = errors[np.isfinite(errors)]
    if not errors.size:
        return {}
    magnitude = np.abs(errors)
    return {f"{key}_{unit}": float(magnitude.mean()), f"{key}_rms_{unit}": float(np.sqrt(np.mean(errors ** 2))),
            f"{key}_p95_{unit}": float(np.percentile(magnitude, 95)), f"{key}_max_{unit}": float(magnitude.max()),
            f"{key}_bias_{unit}": float(errors.mean()), f"{key}_sd_{unit}": float(errors.std())}


def comfort(truth: TruthSeries, vehicle_ids: Sequence[str]) -> dict[str, float]:
    max_accel, jerks = 0.0, []
    for vid in vehicle_ids:
        accel = truth.get(vid, "accel_mps2")
        valid = np.isfinite(accel)
        if valid.sum() < 2:
            continue
        max_accel = max(max_accel, float(np.abs(accel[valid]).max()))
        jerks.append(np.diff(accel[valid]) / np.diff(truth.time_s[valid]))
    all_jerk = np.concatenate(jerks) if jerks else np.zeros(1)
    return {"max_abs_accel_mps2": max_accel, "rms_jerk_mps3": float(np.sqrt(np.mean(all_jerk ** 2)))}


def hard_brakes(truth: TruthSeries, vehicle_ids: Sequence[str]) -> dict[str, float]:
    """`hard_brakes`: how often a judged vehicle starts to decelerate harder than HARD_BRAKE_MPS2 (a lasting brake
    counts once); `phantom_brakes`: those of them that no vehicle near its path called for in the BRAKE_BUILD_UP_S
    before (the false positive of automatic emergency braking). Near the path: ahead, with a footprint in the path
    (a car cutting in or crossing), or going the same way in the next lane, which a merge makes a car's own (a merger
    slowing to slot in behind it, its partner opening the gap for the merger)."""
    judged, braking = set(vehicle_ids), set()
    onsets = phantoms = 0
    for index, (time_s, vehicles) in enumerate(truth.frames):
        now = {v.vehicle_id for v in vehicles if v.vehicle_id in judged and v.accel_mps2 < -HARD_BRAKE_MPS2}
        for vehicle_id in sorted(now - braking):
            onsets += 1
            window = itertools.takewhile(lambda frame: time_s - frame[0] <= BRAKE_BUILD_UP_S,
                                         (truth.frames[k] for k in range(index, -1, -1)))
            phantoms += not any(_brake_called_for(own, other)
                                for _, earlier in window
                                for own in earlier if own.vehicle_id == vehicle_id
                                for other in earlier if other is not own)
        braking = now
    return {"hard_brakes": float(onsets), "phantom_brakes": float(phantoms)}


def _brake_called_for(vehicle: sim_pb2.VehicleTruth, other: sim_pb2.VehicleTruth) -> bool:
    """Whether `other`, if near the vehicle's path, brakes beyond comfort or would be reached within
    CALLED_FOR_TIME_TO_COLLISION_S at the speeds of the moment (measured along the vehicle's heading)."""
    forward = np.array([math.cos(vehicle.heading_rad), math.sin(vehicle.heading_rad)])
    left = np.array([-forward[1], forward[0]])
    bumper_ahead_m = vehicle.length_m - rear_overhang_m(vehicle.length_m)
    front_m = np.array([vehicle.x_m, vehicle.y_m]) + bumper_ahead_m * forward
    corners = _corners(other) - front_m
    along_m, across_m = corners @ forward, corners @ left
    same_way = math.cos(other.heading_rad - vehicle.heading_rad) > 0.0
    reach_m = vehicle.width_m / 2.0 + (LANE_WIDTH_M if same_way else PATH_MARGIN_M)
    if along_m.max() <= 0.0 or across_m.min() > reach_m or across_m.max() < -reach_m:
        return False
    closing_mps = vehicle.speed_mps - other.speed_mps * math.cos(other.heading_rad - vehicle.heading_rad)
    return (other.accel_mps2 <= -CALLED_FOR_DECEL_MPS2
            or max(along_m.min(), 0.0) < CALLED_FOR_TIME_TO_COLLISION_S * closing_mps)


SpeedReference = Callable[[np.ndarray], np.ndarray]


def leading_lane_platoon(truth: TruthSeries) -> list[str]:
    """The platoon of a run whose scenario names none: the vehicles in the first vehicle's lane at the first
    sample, front to back."""
    _, vehicles = truth.frames[0]
    if not vehicles:
        return []
    lane = vehicles[0].lane_index
    in_lane = [v for v in vehicles if v.lane_index == lane]
    return [v.vehicle_id for v in sorted(in_lane, key=lambda v: v.station_m, reverse=True)]


def judged_pairs(platoon: Sequence[str], followers: Sequence[str]) -> list[tuple[str, str]]:
    """(predecessor, follower) for each listed follower in the platoon (leader first)."""
    return [(leader, follower) for leader, follower in zip(platoon, platoon[1:]) if follower in followers]


def predecessor_speed_references(truth: TruthSeries, platoon: Sequence[str],
                                 followers: Sequence[str]) -> dict[str, SpeedReference]:
    """Each listed follower's reference speed is its predecessor's in the platoon."""
    return {follower: (lambda _t, speeds=truth.get(leader, "speed_mps"): speeds)
            for leader, follower in judged_pairs(platoon, followers)}


def speed_error(truth: TruthSeries, reference_mps: Mapping[str, SpeedReference]) -> dict[str, float]:
    """Actual minus reference speed in km/h, over the vehicles given a reference (a function of time)."""
    errors = [truth.get(vid, "speed_mps") - ref(truth.time_s) for vid, ref in reference_mps.items()]
    return error_stats(np.concatenate(errors) * KMH_PER_MPS, "speed_error", "kmh") if errors else {}


def spacing_error(truth: TruthSeries, platoon: Sequence[str], vehicle_ids: Sequence[str],
                  standstill_m: float = DEFAULT_STANDSTILL_M, headway_s: float = DEFAULT_HEADWAY_S) -> dict[str, float]:
    """Gap minus the desired d = r + h v (eq. 4 Heudiasyc) of each listed follower to its predecessor in the
    platoon (leader first), over the samples that hold both: the policy a platoon follows, so a vehicle that is
    in no platoon (a car behind an ambulance driving away, platoon leaders before a merge) is not judged on it."""
    pairs = judged_pairs(platoon, set(vehicle_ids))
    errors = []
    for _, vehicles in truth.frames:
        by_id = {v.vehicle_id: v for v in vehicles}
        for leader_id, follower_id in pairs:
            leader, follower = by_id.get(leader_id), by_id.get(follower_id)
            if leader is not None and follower is not None:
                errors.append(bumper_gap_m(leader, follower) - (standstill_m + headway_s * follower.speed_mps))
    return error_stats(np.array(errors), "spacing_error", "m")


def lateral_error(truth: TruthSeries, vehicle_ids: Sequence[str]) -> dict[str, float]:
    errors = [truth.get(vid, "lateral_offset_m") for vid in vehicle_ids]
    return error_stats(np.concatenate(errors), "lateral_error", "m") if errors else {}


def position_rmse_m(estimate_time_s: np.ndarray, estimate_xy_m: np.ndarray, true_time_s: np.ndarray,
                    true_xy_m: np.ndarray) -> float:
    """RMS horizontal error of the estimates against the truth interpolated at the estimates' times."""
    estimate_time_s = np.asarray(estimate_time_s, dtype=float)
    inside = (estimate_time_s >= true_time_s[0]) & (estimate_time_s <= true_time_s[-1])
    if not inside.any():
        return math.nan
    est = np.asarray(estimate_xy_m, dtype=float)[inside]
    true_x = np.interp(estimate_time_s[inside], true_time_s, true_xy_m[:, 0])
    true_y = np.interp(estimate_time_s[inside], true_time_s, true_xy_m[:, 1])
    return float(np.sqrt(np.mean((est[:, 0] - true_x) ** 2 + (est[:, 1] - true_y) ** 2)))


def identity_switches(associations: Sequence[Mapping[str, int]]) -> int:
    """Times a true vehicle's track id changes from one frame to a later one (a gap does not reset it)."""
    last: dict[str, int] = {}
    switches = 0
    for frame in associations:
        for vehicle_id, track_id in frame.items():
            if vehicle_id in last and last[vehicle_id] != track_id:
                switches += 1
            last[vehicle_id] = track_id
    return switches


def judge(truth: TruthSeries, platoon: Sequence[str] = (), automated: Sequence[str] | None = None,
          reference_speed_mps: Mapping[str, SpeedReference] | None = None,
          safety_radius_m: float = DEFAULT_SAFETY_RADIUS_M, standstill_m: float = DEFAULT_STANDSTILL_M,
          headway_s: float = DEFAULT_HEADWAY_S, string_start_s: float = 0.0,
          string_frequency_hz: float | None = None, string_end_s: float = math.inf,
          position_estimates: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None,
          ours: Collection[str] | None = None) -> dict[str, float]:
    """The run's metrics; `platoon` lists vehicle ids leader first for the string gain, the spacing error and,
    unless `reference_speed_mps` says otherwise, the speed error (each judged follower against its predecessor;
    without a platoon neither error is reported);
    `position_estimates` maps a vehicle id to (time_s (N,), xy_m (N, 2)) of the stack's own estimate;
    `ours`: the scenario's own vehicles among SUMO's traffic (None: every vehicle is), for the pairs judged."""
    judged = list(automated) if automated is not None else sorted(truth.automated) or truth.vehicle_ids
    metrics: dict[str, float] = {
        "collisions": float(collisions(truth, ours)),
        "safety_circle_violations": float(safety_circle_violations(truth, safety_radius_m, ours)),
        "crossing_circle_violations": float(crossing_circle_violations(truth, safety_radius_m, ours))}
    metrics.update(gaps(truth, ours))
    metrics.update(comfort(truth, judged))
    metrics.update(hard_brakes(truth, judged))
    metrics.update(spacing_error(truth, platoon, judged, standstill_m, headway_s))
    metrics.update(lateral_error(truth, judged))
    metrics.update(signal_metrics(truth.signal_frames(), judged))
    if reference_speed_mps is None:
        reference_speed_mps = predecessor_speed_references(truth, platoon, judged)
    if reference_speed_mps:
        metrics.update(speed_error(truth, reference_speed_mps))
    metrics.update(judged_string_gains(truth.time_s, [truth.get(vid, "speed_mps") for vid in platoon],
                                       string_start_s, string_end_s, string_frequency_hz))
    if position_estimates:
        squared, count = 0.0, 0
        for vid, (time_s, xy_m) in position_estimates.items():
            true_xy = np.column_stack((truth.get(vid, "x_m"), truth.get(vid, "y_m")))
            rmse = position_rmse_m(time_s, xy_m, truth.time_s, true_xy)
            times = np.asarray(time_s)
            used = int(np.count_nonzero((times >= truth.time_s[0]) & (times <= truth.time_s[-1])))
            if math.isfinite(rmse):
                squared += rmse ** 2 * used
                count += used
        if count:
            metrics["position_rmse_m"] = math.sqrt(squared / count)
    return metrics
