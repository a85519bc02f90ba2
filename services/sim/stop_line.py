"""StopLine: where an approach's stop line is, what its signal shows, and how far before it a vehicle's front bumper
is."""
from __future__ import annotations

import math
from dataclasses import dataclass

from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.services.sim.signal_controller import SignalAspect, SignalController
from coopdrive.v1 import sim_pb2

# A vehicle more than this far off its heading is not driving along the approach (it crosses it, or comes back).
HEADING_GATE_RAD = math.radians(45.0)


@dataclass(frozen=True)
class StopLine:
    intersection_id: int
    signal_group: int
    road_id: str
    lane: LaneGeometry
    station_m: float
    box_length_m: float
    controller: SignalController

    def aspect(self, time_s: float) -> SignalAspect:
        return self.controller.aspect(self.signal_group, time_s)

    def amber_end_s(self, time_s: float) -> float:
        """When the group's amber ends (its next red begins); now when it is red."""
        return self.controller.next_red_s(self.signal_group, time_s)

    def front_distance_m(self, truth: sim_pb2.VehicleTruth) -> float | None:
        """How far the vehicle's front bumper is before the stop line (negative once past it), for a vehicle in
        this lane driving its way; None for any other."""
        station_m, lateral_m, heading, _ = self.lane.project(truth.x_m, truth.y_m)
        if abs(lateral_m) > 0.5 * self.lane.width_m:
            return None
        if abs(math.remainder(truth.heading_rad - heading, math.tau)) > HEADING_GATE_RAD:
            return None
        front_m = truth.length_m - rear_overhang_m(truth.length_m)
        return self.station_m - (station_m + front_m)
