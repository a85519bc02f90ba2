"""Signal awareness: fed the decoded MAPEMs and SPATEMs as they come, asked where the ego stands at a time.

The answer (`SignalView`) names the ingress lane matched, its stop line's distance, the signal group of the ego's
intended movement and that group's phases on the stack clock, or why there is none: no MAP, no lane matched, no
signal group for the movement, no SPaT, stale SPaT, SPaT that contradicted itself, an intersection reporting
failure.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap.intersection_lanes import intersection_key, reference_plane
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v2x.timebase import ItsClock

from ..config import Intention, SignalConfig
from .lane_match import LaneMatch, MatchTolerance, match_on_lane, nearest_match
from .lanes import IngressLane, ingress_lanes
from .phases import GroupTiming
from .spat_tracker import SpatTracker


class SignalStatus(enum.Enum):
    NO_MAP = enum.auto()
    NO_LANE = enum.auto()
    NO_GROUP = enum.auto()
    NO_SPAT = enum.auto()
    STALE = enum.auto()
    CONTRADICTORY = enum.auto()
    FAILED = enum.auto()
    OK = enum.auto()


@dataclass(frozen=True)
class SignalView:
    status: SignalStatus
    match: LaneMatch | None = None
    signal_group: int | None = None
    timing: GroupTiming | None = None
    why: str = ""
    # Matched to no lane: the rear axle's distance along the heading to the nearest signalised stop line ahead of it
    # with our direction of travel and near our path (the MAP does not match the road), if any.
    unmatched_stop_line_m: float | None = None

    @property
    def on_signalised_lane(self) -> bool:
        """Matched to an ingress lane whose movement has a signal group."""
        return self.signal_group is not None


@dataclass(frozen=True)
class _MappedIntersection:
    plane: LocalTangentPlane
    lanes: tuple[IngressLane, ...]


class SignalAwareness:
    def __init__(self, config: SignalConfig, clock: ItsClock) -> None:
        self.config = config
        self.tracker = SpatTracker(clock, config.timing_tolerance_s)
        self.intersections: dict[tuple[int, int], _MappedIntersection] = {}
        self.tolerance = MatchTolerance(config.lane_half_width_m, config.match_margin_m,
                                        math.radians(config.heading_tolerance_deg), config.box_length_m)

    def on_mapem(self, content: pb.MapemContent) -> None:
        for intersection in content.intersections:
            plane = reference_plane(intersection)
            lanes = ingress_lanes(intersection, plane) if plane is not None else []
            if lanes:
                self.intersections[intersection_key(intersection.id)] = _MappedIntersection(plane, tuple(lanes))

    def on_spatem(self, content: pb.SpatemContent, received_s: float) -> None:
        self.tracker.on_spatem(content, received_s)

    def match(self, latitude_deg: float, longitude_deg: float, heading_rad: float) -> LaneMatch | None:
        candidates = []
        for mapped in self.intersections.values():
            east_m, north_m, _ = mapped.plane.to_enu(latitude_deg, longitude_deg)
            candidates += [m for lane in mapped.lanes
                           if (m := match_on_lane(lane, (east_m, north_m), heading_rad, self.tolerance)) is not None]
        return nearest_match(candidates)

    def unmatched_stop_line_m(self, latitude_deg: float, longitude_deg: float, heading_rad: float) -> float | None:
        """Along the heading to the nearest stop line ahead of a signalised lane that runs our way, within
        mismatch_lateral_m of our path and at most the lane's length away."""
        ux, uy = math.cos(heading_rad), math.sin(heading_rad)
        ahead = []
        for mapped in self.intersections.values():
            east_m, north_m, _ = mapped.plane.to_enu(latitude_deg, longitude_deg)
            for lane in mapped.lanes:
                dx, dy = lane.stop_line[0] - east_m, lane.stop_line[1] - north_m
                along_m, aside_m = dx * ux + dy * uy, abs(dy * ux - dx * uy)
                turned = abs(math.remainder(lane.heading_at_stop_line_rad() - heading_rad, math.tau))
                if (lane.signalised and 0.0 < along_m <= lane.length_m and aside_m <= self.config.mismatch_lateral_m
                        and turned <= self.tolerance.heading_rad):
                    ahead.append(along_m)
        return min(ahead, default=None)

    def view(self, now_s: float, latitude_deg: float, longitude_deg: float, heading_rad: float,
             intention: Intention = Intention.STRAIGHT) -> SignalView:
        if not self.intersections:
            return SignalView(SignalStatus.NO_MAP, why="no MAPEM heard")
        match = self.match(latitude_deg, longitude_deg, heading_rad)
        if match is None:
            ahead_m = self.unmatched_stop_line_m(latitude_deg, longitude_deg, heading_rad)
            why = "on no ingress lane of the MAP" + ("" if ahead_m is None else
                                                      f", a signalised stop line {ahead_m:.0f} m ahead")
            return SignalView(SignalStatus.NO_LANE, why=why, unmatched_stop_line_m=ahead_m)
        group = match.lane.signal_group(intention)
        lane = f"intersection {match.lane.intersection[1]} lane {match.lane.lane_id}"
        if group is None:
            return SignalView(SignalStatus.NO_GROUP, match, why=f"{lane}: no signal group goes {intention.name}")
        return self._timed(now_s, match, group, lane)

    def _timed(self, now_s: float, match: LaneMatch, group: int, lane: str) -> SignalView:
        key = self.tracker.find(match.lane.intersection, group)
        where = f"{lane} signal group {group}"
        if key is None:
            return SignalView(SignalStatus.NO_SPAT, match, group, why=f"{where}: no SPATEM heard")
        timing = self.tracker.latest[key]
        contradiction = self.tracker.contradictions.get(key)
        age_s = now_s - timing.received_s
        if age_s > self.config.stale_after_s(self.tracker.period_s(key)):
            return SignalView(SignalStatus.STALE, match, group, timing, f"{where}: SPaT {age_s:.1f} s old")
        if contradiction is not None and now_s - contradiction.at_s <= self.config.contradiction_hold_s:
            return SignalView(SignalStatus.CONTRADICTORY, match, group, timing, f"{where}: {contradiction.why}")
        if timing.failed:
            return SignalView(SignalStatus.FAILED, match, group, timing, f"{where}: the intersection reports failure")
        return SignalView(SignalStatus.OK, match, group, timing, where)
