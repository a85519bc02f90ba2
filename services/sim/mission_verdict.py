"""MissionJudge: the verdict of a scenario-file run from its ground truth, and the judge's metrics.

A run fails on any collision; beyond that each mission has its own goal, and a failure says which vehicles
missed it so a user sees why (e.g. merge: who was still in the closed lane at the end).
"""

from __future__ import annotations

import functools
import math
from typing import Sequence

from coopdrive.services.sim import metrics as judging
from coopdrive.services.sim.fault_config import ServiceCrash, V2vLoss
from coopdrive.services.sim.roadside_unit import RsuEventKind
from coopdrive.services.sim.scenario_config import Mission, ScenarioConfig, VehicleRole
from coopdrive.services.sim.signal_fault_reactions import FaultReaction, fault_reactions
from coopdrive.services.sim.signal_metrics import Crossing, crossings
from coopdrive.services.sim.truth_series import TruthSeries
from coopdrive.v1 import actuation_pb2, sim_pb2

# A vehicle counts as having crossed the competition zone once it was inside it and then this far out.
ZONE_EXIT_MARGIN_M = 5.0
# GCDC: a merge completes in under 10 s per vehicle pair.
MERGE_TIME_LIMIT_S = 10.0
# A vehicle this far off its lane centre is changing lane.
LANE_CENTRE_TOLERANCE_M = 0.3


class MissionJudge:
    def __init__(self, config: ScenarioConfig, stack_ids: Sequence[str]):
        self.config = config
        self.stack_ids = list(stack_ids)
        self.frames: list[tuple[float, list[sim_pb2.VehicleTruth]]] = []
        # Each frame's signalised approaches (none in a world without traffic lights).
        self.signals: list[list[sim_pb2.SignalTruth]] = []
        self.collisions = 0
        # Pairs of SUMO's vehicles (in the truth, not in the scenario) are not judged: one of ours must be in a pair.
        self.ours = frozenset(v.vehicle_id for v in config.vehicles) if config.sumo_traffic is not None else None
        self._metrics: dict[str, float] | None = None
        # Stack vehicles whose actuation once drove them, and when each first gave the car back to its driver.
        self._automated: set[str] = set()
        self.automation_lost_s: dict[str, float] = {}
        # Stack vehicle -> when each of its safe stops began (from its CAN commands' driving mode).
        self.safe_stop_onsets_s: dict[str, list[float]] = {}
        self._in_safe_stop: dict[str, bool] = {}

    def observe(self, time_s: float, truth: sim_pb2.GroundTruth) -> None:
        self.frames.append((time_s, list(truth.vehicles)))
        if truth.signals:
            self.signals.append(list(truth.signals))
        self._metrics = None
        # Onsets in the newest pair of frames, less the contacts already there in the older one.
        newest = judging.collisions(TruthSeries.from_frames(self.frames[-2:]), self.ours)
        older = (judging.collisions(TruthSeries.from_frames(self.frames[-2:-1]), self.ours)
                 if len(self.frames) >= 2 else 0)
        self.collisions += newest - older

    def observe_automation(self, vehicle_id: str, longitudinal_active: bool, time_s: float) -> None:
        """A stack's CAN command: an automated vehicle that falls back to its driver (an override read where
        there is none, a safe stop into manual) has failed its mission even if nothing hit anything."""
        if longitudinal_active:
            self._automated.add(vehicle_id)
        elif vehicle_id in self._automated:
            self.automation_lost_s.setdefault(vehicle_id, time_s)
            self._metrics = None

    def metrics(self) -> dict[str, float]:
        if self._metrics is None:
            judging_config = self.config.judging
            series = TruthSeries.from_frames(self.frames, self.signals) if self.frames else None
            if series is None:
                return {"collisions": 0.0}
            platoon = [v for v in judging_config.platoon if v in series.vehicle_ids]
            self._metrics = {key: value for key, value in judging.judge(
                series, platoon=platoon, automated=self.stack_ids, safety_radius_m=judging_config.safety_radius_m,
                standstill_m=judging_config.standstill_m, headway_s=judging_config.headway_s,
                string_start_s=judging_config.string_start_s,
                string_frequency_hz=judging_config.string_frequency_hz,
                string_end_s=judging_config.string_end_s, ours=self.ours).items() if math.isfinite(value)}
            self._metrics["collisions"] = float(self.collisions)
            self._metrics["automation_lost"] = float(len(self.automation_lost_s))
            self._metrics["safe_stops"] = float(sum(map(len, self.safe_stop_onsets_s.values())))
            reactions_s = self.crash_to_safe_stop_s()
            if reactions_s:
                self._metrics["crash_to_safe_stop_s"] = max(reactions_s.values())
            if self.config.mission is Mission.MERGE:
                self._metrics.update(self._merge_metrics())
            if self.config.mission is Mission.EMERGENCY and math.isfinite(self.corridor_close_time_s()):
                self._metrics["corridor_close_time_s"] = self.corridor_close_time_s()
            crossing_times = self.crossing_times_s() if self.config.mission is Mission.INTERSECTION else {}
            if crossing_times:
                self._metrics["crossing_time_s"] = max(crossing_times.values())
        return self._metrics

    def observe_mode(self, vehicle_id: str, driving_mode: int, time_s: float) -> None:
        """A stack's CAN command's driving mode: when each safe stop began."""
        safe_stop = driving_mode == actuation_pb2.DRIVING_MODE_SAFE_STOP
        if safe_stop and not self._in_safe_stop.get(vehicle_id, False):
            self.safe_stop_onsets_s.setdefault(vehicle_id, []).append(time_s)
            self._metrics = None
        self._in_safe_stop[vehicle_id] = safe_stop

    def _crash_starts_s(self) -> dict[str, float]:
        """Each stack vehicle's first service_crash."""
        starts: dict[str, float] = {}
        for fault in self.config.faults:
            if isinstance(fault, ServiceCrash):
                starts[fault.vehicle_id] = min(fault.start_s, starts.get(fault.vehicle_id, math.inf))
        return starts

    def _first_fault_s(self, vehicle_id: str) -> float:
        """When the first fault of the scenario that concerns the vehicle (it or every vehicle) begins."""
        return min((fault.start_s for fault in self.config.faults if fault.concerns(vehicle_id)), default=math.inf)

    def unexpected_safe_stops_s(self) -> dict[str, float]:
        """Per stack vehicle, its first safe stop that no fault of the scenario explains: a car halting in its
        lane because its own stack gave up (localisation lost, a service silent) has failed its mission."""
        return {vehicle_id: onsets[0] for vehicle_id, onsets in self.safe_stop_onsets_s.items()
                if onsets and onsets[0] < self._first_fault_s(vehicle_id)}

    def crash_to_safe_stop_s(self) -> dict[str, float]:
        """Per stack vehicle whose service the scenario crashed, how long after the crash its safe stop began."""
        starts = self._crash_starts_s()
        return {vehicle_id: min(after) - starts[vehicle_id] for vehicle_id, onsets in self.safe_stop_onsets_s.items()
                if (after := [t for t in onsets if t >= starts.get(vehicle_id, math.inf)])}

    def verdict(self) -> tuple[bool, str]:
        if not self.frames:
            return False, "the run ended before any ground truth"
        if self.collisions:
            return False, f"{self.collisions} collision(s)"
        # The driver taking back a car whose stack the scenario crashed is the fallback the crash tests, not a
        # failure (its timing is crash_to_safe_stop_s); a collision still fails the run.
        crash_starts_s = self._crash_starts_s()
        unexpected = {v: t for v, t in self.automation_lost_s.items() if t < crash_starts_s.get(v, math.inf)}
        if unexpected:
            lost = ", ".join(f"{v} at {t:.1f} s" for v, t in sorted(unexpected.items(), key=lambda kv: kv[1]))
            return False, f"automation lost: {lost}"
        stopped = self.unexpected_safe_stops_s()
        if stopped:
            return False, "safe stop: " + ", ".join(f"{v} at {t:.1f} s"
                                                     for v, t in sorted(stopped.items(), key=lambda kv: kv[1]))
        ran_red = self.red_light_crossings()
        if ran_red:
            return False, "red-light violation: " + ", ".join(
                f"{c.vehicle_id} at {c.time_s:.1f} s (intersection {c.intersection_id}, group {c.signal_group})"
                for c in ran_red)
        mission = self.config.mission
        if mission is Mission.PLATOON:
            gain = self.metrics().get("string_gain")
            excited = self.config.judging.string_frequency_hz is not None
            if excited and gain is not None and gain >= 1.0 and not self._v2v_cut_while_judging_string():
                return False, f"string unstable: string gain {gain:.3f} >= 1"
        elif mission is Mission.MERGE:
            return self._merge_verdict()
        elif mission is Mission.INTERSECTION:
            return self._intersection_verdict()
        elif mission is Mission.EMERGENCY:
            return self._emergency_verdict()
        return True, ""

    def red_light_crossings(self) -> list[Crossing]:
        """The stacks' crossings of a stop line on red (signal_metrics.py)."""
        return [c for c in crossings(self._signal_frames()) if c.red and c.vehicle_id in self.stack_ids]

    def fault_reactions(self) -> list[FaultReaction]:
        """What each stack did about each fault of a signalised intersection's roadside unit
        (signal_fault_reactions.py)."""
        return fault_reactions(self.config.faults, self.config.roadside_units, self._signal_frames(), self.stack_ids)

    def _signal_frames(self) -> list:
        return [(t, vehicles, signals) for (t, vehicles), signals in zip(self.frames, self.signals)]

    def _v2v_cut_while_judging_string(self) -> bool:
        """Every V2V packet of every vehicle lost during the judged oscillation. The platoon then runs on its
        radar-only fallbacks at a raised gap, and what is asked of it is no collision (checked before); its
        string gain is still reported, but the wave it damps to a few cm/s leaves ratios of noise."""
        judging_config = self.config.judging
        return any(isinstance(fault, V2vLoss) and fault.vehicle_id is None and fault.loss_probability >= 1.0
                   and fault.start_s < judging_config.string_end_s and fault.end_s > judging_config.string_start_s
                   for fault in self.config.faults)

    def _final(self) -> dict[str, sim_pb2.VehicleTruth]:
        return {v.vehicle_id: v for v in self.frames[-1][1]}

    def _roadworks(self) -> list:
        return [event for unit in self.config.roadside_units for event in unit.events
                if event.kind is RsuEventKind.ROADWORKS]

    def _merge_verdict(self) -> tuple[bool, str]:
        works = self._roadworks()
        intruders = sorted({v.vehicle_id for _, vehicles in self.frames for v in vehicles
                            if v.vehicle_id in self.stack_ids and any(_in_works(v, event) for event in works)})
        if intruders:
            return False, f"{', '.join(intruders)} drove into the road works"
        closed = {event.closed_lane for event in works}
        final = self._final()
        still = sorted(v for v in self.stack_ids if v in final and final[v].lane_index in closed)
        if still:
            return False, f"merge not completed: {', '.join(still)} still in the closed lane at the end"
        slow = {v: end - start for v, (start, end) in self.lane_changes_s().items() if end - start > MERGE_TIME_LIMIT_S}
        if slow:
            return False, "lane change too slow: " + ", ".join(f"{v} {t:.1f} s" for v, t in sorted(slow.items()))
        return True, ""

    def _merge_metrics(self) -> dict[str, float]:
        """merge_time_s: from the road-works notice (the roadside unit's first DENM) to the last merger settled
        in the open lane, the whole manoeuvre as the organisers timed it; lane_change_time_s: the slowest lane
        change alone (leaving the closed lane's centre to settling in the new one), what GCDC limits to 10 s."""
        changes = self.lane_changes_s()
        if not changes:
            return {}
        figures = {"lane_change_time_s": max(end - start for start, end in changes.values())}
        notices_s = [event.time_s for event in self._roadworks()]
        if notices_s:
            figures["merge_time_s"] = max(end for _, end in changes.values()) - min(notices_s)
        return figures

    def lane_changes_s(self) -> dict[str, tuple[float, float]]:
        """Per stack vehicle that left a closed lane: (left its centre, settled in the new lane) times."""
        closed = {event.closed_lane for event in self._roadworks()}

        def off_centre(v: sim_pb2.VehicleTruth) -> bool:
            return abs(v.lateral_offset_m) > LANE_CENTRE_TOLERANCE_M

        return self._spans_s(begins=lambda v: v.lane_index in closed and off_centre(v),
                             ends=lambda v: v.lane_index not in closed and not off_centre(v))

    def _spans_s(self, begins, ends) -> dict[str, tuple[float, float]]:
        """Per stack vehicle: (start, end) from the first frame where begins(v) holds to the first later one
        where ends(v) does; vehicles that never got to the end are left out."""
        started: dict[str, float] = {}
        spans: dict[str, tuple[float, float]] = {}
        for time_s, vehicles in self.frames:
            for v in vehicles:
                if v.vehicle_id not in self.stack_ids or v.vehicle_id in spans:
                    continue
                if begins(v):
                    started.setdefault(v.vehicle_id, time_s)
                elif v.vehicle_id in started and ends(v):
                    spans[v.vehicle_id] = (started[v.vehicle_id], time_s)
        return spans

    def _intersection_verdict(self) -> tuple[bool, str]:
        if self._competition_zone is None:
            return False, f"map {self.config.map} has no competition zone to cross"
        missing = sorted(set(self.stack_ids) - set(self.crossing_times_s()))
        if missing:
            return False, f"intersection not crossed by {', '.join(missing)}"
        violations = int(self.metrics().get("crossing_circle_violations", 0))
        if violations:
            return False, f"{violations} safety circle violation(s) between crossing vehicles"
        return True, ""

    @functools.cached_property
    def _competition_zone(self):
        from coopdrive.roadmap import RoadMap

        zones = RoadMap.load(self.config.map).zones
        # The map's competition zone; a map may also mark its reference point as a zone of radius 0.
        return max(zones.values(), key=lambda z: z.radius_m) if zones else None

    def crossing_times_s(self) -> dict[str, float]:
        """Per stack vehicle that crossed the competition zone: from entering it to being ZONE_EXIT_MARGIN_M out."""
        zone = self._competition_zone
        if zone is None:
            return {}

        def distance_m(v: sim_pb2.VehicleTruth) -> float:
            return math.hypot(v.x_m - zone.x_m, v.y_m - zone.y_m)

        spans = self._spans_s(begins=lambda v: distance_m(v) <= zone.radius_m,
                              ends=lambda v: distance_m(v) > zone.radius_m + ZONE_EXIT_MARGIN_M)
        return {vehicle_id: end - start for vehicle_id, (start, end) in spans.items()}

    def _emergency_verdict(self) -> tuple[bool, str]:
        emergency = self._emergency_id()
        final = self._final()
        if emergency is None or emergency not in final:
            return False, "no emergency vehicle in the run"
        passer = final[emergency]
        behind = sorted(v for v in self.stack_ids if v in final and final[v].station_m > passer.station_m)
        if behind:
            return False, f"the emergency vehicle did not get past {', '.join(behind)}"
        aside = sorted(v for v in self.stack_ids if v in final
                       and abs(final[v].lateral_offset_m) > LANE_CENTRE_TOLERANCE_M)
        if aside:
            return False, f"corridor not closed: {', '.join(aside)} still off the lane centre at the end"
        return True, ""

    def _emergency_id(self) -> str | None:
        return next((v.vehicle_id for v in self.config.vehicles if v.role is VehicleRole.EMERGENCY), None)

    def corridor_close_time_s(self) -> float:
        """From the emergency vehicle passing the last stack vehicle to every stack vehicle back within
        LANE_CENTRE_TOLERANCE_M of its lane centre; NaN while that has not happened."""
        emergency, passed_s = self._emergency_id(), None
        for time_s, vehicles in self.frames:
            by_id = {v.vehicle_id: v for v in vehicles}
            stacks = [by_id[v] for v in self.stack_ids if v in by_id]
            if emergency not in by_id or not stacks:
                continue
            if passed_s is None and all(v.station_m < by_id[emergency].station_m for v in stacks):
                passed_s = time_s
            if passed_s is not None and all(abs(v.lateral_offset_m) <= LANE_CENTRE_TOLERANCE_M for v in stacks):
                return time_s - passed_s
        return math.nan


def _in_works(vehicle: sim_pb2.VehicleTruth, event) -> bool:
    """In the closed lane between the works' start (the DENM event position) and its end, along the road."""
    if vehicle.lane_index != event.closed_lane:
        return False
    along_m = ((vehicle.x_m - event.x_m) * math.cos(vehicle.heading_rad)
               + (vehicle.y_m - event.y_m) * math.sin(vehicle.heading_rad))
    return 0.0 <= along_m <= event.length_m
