"""How well each stack's scene tracked the vehicles around it, judged against the simulator's truth.

For every scene a stack published, each true vehicle within TRACKING_RANGE_M of the observer is matched to
the nearest scene object within the association gate of its rear bumper centre (the scene's reference point).
An object no true vehicle's footprint comes within the gate of is a false object; how long the longest one
lasted is what the scene issue bounds (0.5 s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from coopdrive.judging.run_messages import RunMessages
from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim import geometry
from coopdrive.services.sim import metrics as judge_metrics
from coopdrive.services.sim.truth_series import TruthSeries

TRACKING_RANGE_M = 80.0
SECONDS_PER_10_MIN = 600.0


@dataclass(frozen=True)
class _Pose:
    """One vehicle's truth at the scene times of one observer, (M,) arrays, NaN while absent."""

    x_m: np.ndarray
    y_m: np.ndarray
    heading_rad: np.ndarray
    length_m: np.ndarray
    width_m: np.ndarray

    @classmethod
    def at(cls, series: TruthSeries, vehicle_id: str, times_s: np.ndarray) -> _Pose:
        present = np.isfinite(series.get(vehicle_id, "x_m"))
        if not present.any():
            nan = np.full(times_s.size, np.nan)
            return cls(nan, nan, nan, nan, nan)
        known_s = series.time_s[present]
        inside = (times_s >= known_s[0]) & (times_s <= known_s[-1])

        def interpolated(name: str) -> np.ndarray:
            return np.where(inside, np.interp(times_s, known_s, series.get(vehicle_id, name)[present]), np.nan)

        # Heading is taken from the nearest sample: interpolating across +-pi would turn the car around.
        nearest = np.clip(np.searchsorted(known_s, times_s), 0, known_s.size - 1)
        heading = np.where(inside, series.get(vehicle_id, "heading_rad")[present][nearest], np.nan)
        return cls(interpolated("x_m"), interpolated("y_m"), heading, interpolated("length_m"),
                   interpolated("width_m"))

    def rear_centre(self, k: int) -> tuple[float, float]:
        back_m = rear_overhang_m(self.length_m[k])
        return (self.x_m[k] - back_m * math.cos(self.heading_rad[k]),
                self.y_m[k] - back_m * math.sin(self.heading_rad[k]))

    def distances_to_body_m(self, k: int, points_xy_m: np.ndarray) -> np.ndarray:
        """Distance from each ENU point (N x 2) to the vehicle's footprint (0 inside it)."""
        local = geometry.to_ego_frame(points_xy_m, self.x_m[k], self.y_m[k], self.heading_rad[k])
        back_m = rear_overhang_m(self.length_m[k])
        outside_along = np.maximum(np.maximum(-back_m - local[:, 0], local[:, 0] - (self.length_m[k] - back_m)), 0.0)
        outside_across = np.maximum(np.abs(local[:, 1]) - 0.5 * self.width_m[k], 0.0)
        return np.hypot(outside_along, outside_across)


@dataclass
class _Tally:
    """What the scenes of a run add up to: errors to nearest objects, matches, identities per scene."""

    gate_m: float
    errors_m: list[float] = field(default_factory=list)
    expected: int = 0
    matched: int = 0
    beyond_gate: int = 0
    longest_false_s: float = 0.0
    # Per scene, "<observer>:<true vehicle>" -> the object id the observer gave it.
    frames: list[dict[str, int]] = field(default_factory=list)

    def match(self, observer: str, k: int, own: _Pose, present: dict[str, _Pose], placed: list,
              range_m: float) -> None:
        """Each vehicle within range against its nearest object in scene k."""
        frame = {}
        for vid, pose in present.items():
            rear_x, rear_y = pose.rear_centre(k)
            if math.hypot(rear_x - own.x_m[k], rear_y - own.y_m[k]) > range_m:
                continue
            self.expected += 1
            nearest = min(((math.hypot(o.position.x_m - rear_x, o.position.y_m - rear_y), o.object_id)
                           for o in placed), default=None)
            if nearest is None:
                continue
            # Every truth that has a nearest object counts towards the percentile, the ones beyond the gate
            # too (they are reported as a count): leaving them out would hide the worst errors.
            self.errors_m.append(nearest[0])
            if nearest[0] >= self.gate_m:
                self.beyond_gate += 1
                continue
            self.matched += 1
            frame[f"{observer}:{vid}"] = nearest[1]
        self.frames.append(frame)

    def false_objects(self, k: int, present: dict[str, _Pose], placed: list) -> set[int]:
        """Objects of scene k farther than the gate from every vehicle's body."""
        if not placed:
            return set()
        placed_xy_m = np.array([[o.position.x_m, o.position.y_m] for o in placed])
        nearest_body_m = np.full(len(placed), np.inf)
        for pose in present.values():
            nearest_body_m = np.minimum(nearest_body_m, pose.distances_to_body_m(k, placed_xy_m))
        return {o.object_id for o, distance_m in zip(placed, nearest_body_m) if distance_m >= self.gate_m}


def tracking_metrics(series: TruthSeries, messages: RunMessages, gate_m: float,
                     range_m: float = TRACKING_RANGE_M) -> dict[str, float]:
    """id_switches (and per tracked vehicle per 10 min), object_position_error_p95_m (over every vehicle within
    range and its nearest object, however far; how many were beyond the gate is
    object_position_errors_beyond_gate), object_coverage_ratio (vehicles within range that had an object within
    the gate) and false_object_max_s; empty without scenes."""
    tally = _Tally(gate_m)
    start_s, end_s = float(series.time_s[0]), float(series.time_s[-1])
    for observer, scenes in sorted(messages.scenes.items()):
        if observer not in series.values:
            continue
        scenes = sorted((s for s in scenes if start_s <= s.header.sample_time_s <= end_s),
                        key=lambda s: s.header.sample_time_s)
        times_s = np.array([s.header.sample_time_s for s in scenes])
        own = _Pose.at(series, observer, times_s)
        others = {vid: _Pose.at(series, vid, times_s) for vid in series.vehicle_ids if vid != observer}
        false_since: dict[int, float] = {}
        for k, scene in enumerate(scenes):
            time_s = float(times_s[k])
            # An object whose position has faded (confidence -1) claims no place to be judged on.
            placed = [o for o in scene.objects if o.position.confidence >= 0]
            present = {vid: pose for vid, pose in others.items() if math.isfinite(pose.x_m[k])}
            tally.match(observer, k, own, present, placed, range_m)
            false_since = {oid: false_since.get(oid, time_s) for oid in tally.false_objects(k, present, placed)}
            tally.longest_false_s = max([tally.longest_false_s] + [time_s - since for since in false_since.values()])
    if tally.expected == 0:
        return {}
    switches = judge_metrics.identity_switches(tally.frames)
    tracked_pairs = {pair for frame in tally.frames for pair in frame}
    duration_s = max(end_s - start_s, 1e-9)
    return {
        "id_switches": float(switches),
        "id_switches_per_vehicle_per_10min": switches / max(len(tracked_pairs), 1) / (duration_s / SECONDS_PER_10_MIN),
        "object_position_error_p95_m": float(np.percentile(tally.errors_m, 95)) if tally.errors_m else math.nan,
        "object_position_errors_beyond_gate": float(tally.beyond_gate),
        "object_coverage_ratio": tally.matched / tally.expected,
        "false_object_max_s": tally.longest_false_s,
    }
