"""The simulated safety driver's steering while lateral automation is off: pure pursuit on the nearest lane.

Without it a vehicle whose stack only controls the speed would leave the curved A270 at its first bend.
"""

from __future__ import annotations

import math
from typing import Sequence

from coopdrive.services.sim.road_geometry import LaneGeometry, match_lane
from coopdrive.services.sim.vehicle_model import VehicleState

LOOKAHEAD_TIME_S = 1.0
MIN_LOOKAHEAD_M = 8.0


class LaneKeepingDriver:
    def __init__(self, lanes: Sequence[LaneGeometry], wheelbase_m: float, lane_index: int | None = None):
        self._lanes = list(lanes)
        self._wheelbase_m = wheelbase_m
        # The lane the driver keeps to; None: whichever lane the vehicle is nearest to.
        self.lane_index = lane_index

    def steering_rad(self, state: VehicleState) -> float:
        lane = self._lane(state)
        if lane is None:
            return 0.0
        station_m, _, _, _ = lane.project(state.x_m, state.y_m)
        lookahead_m = max(MIN_LOOKAHEAD_M, LOOKAHEAD_TIME_S * state.speed_mps)
        target_x, target_y, _ = lane.pose_at(station_m + lookahead_m, 0.0)
        bearing = math.atan2(target_y - state.y_m, target_x - state.x_m)
        alpha = math.remainder(bearing - state.heading_rad, math.tau)
        distance_m = max(math.hypot(target_x - state.x_m, target_y - state.y_m), 1e-3)
        return math.atan2(2.0 * self._wheelbase_m * math.sin(alpha), distance_m)  # pure pursuit

    def _lane(self, state: VehicleState) -> LaneGeometry | None:
        if self.lane_index is not None:
            for lane in self._lanes:
                if lane.lane_index == self.lane_index:
                    return lane
        found = match_lane(self._lanes, state.x_m, state.y_m, state.heading_rad)
        return None if found is None else found[0]
