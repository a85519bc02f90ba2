"""SignalBroadcaster: what a signalised intersection's roadside unit says, as MAPEM and SPATEM contents.

The MAPEM (intersection_map.py) is built once; the SPATEM at each send states every group's current phase and the
three after it (one whole cycle: red-amber, green, amber, red) with their end times as TimeMarks: seconds after the
start of the current UTC hour, so an end past the hour wraps to its start as on the wire.
"""
from __future__ import annotations

import datetime as dt
from typing import Collection, Sequence

from coopdrive.services.sim.fault_config import Fault, MapLaneOffset, SpatLoss, SpatTimeJump
from coopdrive.services.sim.intersection_config import SignalisedIntersection
from coopdrive.services.sim.intersection_map import LanesOfRoad, ToGeodetic, approach_lane, intersection_map
from coopdrive.services.sim.participants import IntentKind, MessageIntent, RateGate
from coopdrive.services.sim.signal_controller import SignalController
from coopdrive.services.sim.stop_line import StopLine
from coopdrive.v2x.dsrc_time import SECONDS_PER_HOUR, SECONDS_PER_MINUTE
from coopdrive.v2x.its_pdu import PROTOCOL_VERSION_CURRENT
from coopdrive.v1 import infrastructure_pb2 as pb
from coopdrive.v1 import sim_pb2

# The current phase and the three after it: a whole cycle ahead, what a speed advisory needs.
ANNOUNCED_PHASES = 4


class SignalBroadcaster:
    def __init__(self, config: SignalisedIntersection, station_id: int, lanes_of_road: LanesOfRoad,
                 to_geodetic: ToGeodetic, utc_epoch: dt.datetime) -> None:
        self.config = config
        self.station_id = station_id
        self.controller = SignalController(config.plan)
        self._epoch_s = utc_epoch.timestamp()
        self._year_start_s = dt.datetime(utc_epoch.year, 1, 1, tzinfo=dt.timezone.utc).timestamp()
        self.stop_lines = [StopLine(config.intersection_id, a.signal_group, a.road, approach_lane(lanes_of_road, a),
                                    a.stop_station_m, a.box_length_m, self.controller)
                           for a in config.approaches]
        self._lanes_of_road, self._to_geodetic = lanes_of_road, to_geodetic
        self.mapem = self._mapem((0.0, 0.0))
        # What the unit's faults make of its messages (set_faults).
        self.spat_silent = False
        self.time_jump_s = 0.0
        self._misplaced_m = (0.0, 0.0)
        self._mapem_gate = RateGate(config.mapem_rate_hz)
        self._spatem_gate = RateGate(config.spatem_rate_hz)
        self._actuated = any(stage.max_extension_s > 0 for stage in config.plan.stages)

    def _mapem(self, misplaced_m: tuple[float, float]) -> pb.MapemContent:
        mapem = pb.MapemContent(protocol_version=PROTOCOL_VERSION_CURRENT, station_id=self.station_id,
                                message_revision=self.config.revision)
        mapem.intersections.append(intersection_map(self.config, self._lanes_of_road, self._to_geodetic, misplaced_m))
        return mapem

    def set_faults(self, faults: Sequence[Fault]) -> None:
        """The unit's active faults (fault_config.SIGNAL_FAULTS naming it); none restores its messages."""
        self.spat_silent = any(isinstance(f, SpatLoss) for f in faults)
        self.time_jump_s = sum(f.jump_s for f in faults if isinstance(f, SpatTimeJump))
        offsets = [(f.east_m, f.north_m) for f in faults if isinstance(f, MapLaneOffset)]
        misplaced_m = (sum(e for e, _ in offsets), sum(n for _, n in offsets))
        if misplaced_m != self._misplaced_m:
            self._misplaced_m = misplaced_m
            self.mapem = self._mapem(misplaced_m)

    def step(self, now_s: float, truths: Collection[sim_pb2.VehicleTruth]) -> None:
        """Advance the controller; a vehicle within the detector's reach of a stop line calls for its group."""
        reach_m = self.config.plan.detector_m
        calling = set()
        for line in self.stop_lines:
            for truth in truths:
                distance_m = line.front_distance_m(truth)
                if distance_m is not None and 0.0 <= distance_m <= reach_m:
                    calling.add(line.signal_group)
        self.controller.step(now_s, calling)

    def messages_due(self, now_s: float, unit_id: str, x_m: float, y_m: float) -> list[MessageIntent]:
        intents = []
        if self._mapem_gate.due(now_s):
            intents.append(MessageIntent(IntentKind.MAPEM, unit_id, self.station_id, now_s,
                                         {"x_m": x_m, "y_m": y_m, "content": self.mapem}))
        if self._spatem_gate.due(now_s) and not self.spat_silent:
            intents.append(MessageIntent(IntentKind.SPATEM, unit_id, self.station_id, now_s,
                                         {"x_m": x_m, "y_m": y_m, "content": self.spatem(now_s)}))
        return intents

    def _utc_s(self, time_s: float) -> float:
        return self._epoch_s + time_s

    def spatem(self, now_s: float) -> pb.SpatemContent:
        utc_s = self._utc_s(now_s)
        minute_of_year = int((utc_s - self._year_start_s) // SECONDS_PER_MINUTE)
        content = pb.SpatemContent(protocol_version=PROTOCOL_VERSION_CURRENT, station_id=self.station_id,
                                   minute_of_year=minute_of_year)
        intersection = content.intersections.add(revision=self.config.revision, name=self.config.name,
                                                 minute_of_year=minute_of_year,
                                                 second_of_minute_s=round(utc_s % SECONDS_PER_MINUTE, 3))
        intersection.id.id = self.config.intersection_id
        if self.config.region is not None:
            intersection.id.region = self.config.region
        intersection.status.fixed_time_operation = not self._actuated
        intersection.status.traffic_dependent_operation = self._actuated
        for group in self.controller.groups:
            state = intersection.signal_groups.add(signal_group=group)
            for phase in self.controller.phases(group, now_s, ANNOUNCED_PHASES):
                jump_s = self.time_jump_s
                state.events.add(state=int(phase.aspect), min_end_time_s=self._of_hour(phase.min_end_s + jump_s),
                                 max_end_time_s=self._of_hour(phase.max_end_s + jump_s),
                                 likely_time_s=self._of_hour(phase.likely_end_s + jump_s))
        return content

    def _of_hour(self, time_s: float) -> float:
        """A run time as seconds after the start of its UTC hour, to the tenth a TimeMark holds."""
        return round(self._utc_s(time_s) % SECONDS_PER_HOUR, 1)

    def signal_truths(self, now_s: float) -> list[sim_pb2.SignalTruth]:
        """Each approach's stop line and its group's state now."""
        truths = []
        for line in self.stop_lines:
            phase = self.controller.phases(line.signal_group, now_s, count=1)[0]
            x_m, y_m, heading_rad = line.lane.pose_at(line.station_m, 0.0)
            truths.append(sim_pb2.SignalTruth(
                intersection_id=self.config.intersection_id, signal_group=line.signal_group, state=int(phase.aspect),
                phase_end_s=phase.min_end_s, amber_end_s=line.amber_end_s(now_s), stop_x_m=x_m, stop_y_m=y_m,
                heading_rad=heading_rad, lane_width_m=line.lane.width_m))
        return truths
