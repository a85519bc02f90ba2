"""EgoOutput: the geolocator's estimate as the EgoState it publishes: the filter's state predicted to the time asked,
its localisation mode, its geodetic position and its match to the lane map; without a fix, the car's own speed and
yaw rate alone."""

from __future__ import annotations

import math

import numpy as np

from coopdrive.geodesy import LocalTangentPlane
from coopdrive.roadmap import RoadMap
from coopdrive.services.geolocation.bookkeeping import Bookkeeping
from coopdrive.services.geolocation.config import GeolocatorConfig
from coopdrive.services.geolocation.ekf import GeolocationEkf
from coopdrive.services.geolocation.frames import ModeThresholds, localisation_mode
from coopdrive.services.geolocation.motion_models import ACCEL, HEADING, SPEED, VEHICLE_STATE_DIM, YAW_RATE, E, N
from coopdrive.v1 import ego_pb2

SENDER = "geolocation"


class EgoOutput:
    def __init__(self, config: GeolocatorConfig):
        self.config = config
        self._sequence = 0

    def estimate(self, time_s: float, ekf: GeolocationEkf, book: Bookkeeping, plane: LocalTangentPlane,
                 road_map: RoadMap | None, thresholds: ModeThresholds) -> ego_pb2.EgoState:
        """The ego state predicted to time_s from the filter and the bookkeeping (the filter itself is not moved),
        in the geolocator's frame (`plane`, set by the first fix where no origin was given), matched to `road_map`
        and moded by `thresholds` (whose GNSS timeout follows the receiver's rate)."""
        self._sequence += 1
        state = ego_pb2.EgoState()
        state.header.sample_time_s = time_s
        state.header.vehicle_id = self.config.vehicle_id
        state.header.sender = SENDER
        state.header.sequence = self._sequence
        state.last_fix_mode = book.last_fix_mode
        if not ekf.initialised:
            return self._without_position(state, book)
        x, P = ekf.predicted(time_s)
        state.x_m, state.y_m, state.heading_rad = x[E], x[N], x[HEADING]
        state.speed_mps, state.yaw_rate_radps, state.accel_mps2 = x[SPEED], x[YAW_RATE], x[ACCEL]
        state.covariance.extend(P[:VEHICLE_STATE_DIM, :VEHICLE_STATE_DIM].ravel().tolist())
        position_std_m = position_std_m_of(P)
        state.position_std_m = position_std_m
        since_fix_s = None if book.last_fix_time_s is None else time_s - book.last_fix_time_s
        state.mode = localisation_mode(True, position_std_m, since_fix_s, book.last_fix_mode, thresholds,
                                       heading_known=book.heading_known)
        state.latitude_deg, state.longitude_deg, _ = plane.to_geodetic(float(x[E]), float(x[N]))
        if road_map is not None:
            match = road_map.match(x[E], x[N], x[HEADING])
            if match is not None:
                lane = state.lane
                lane.matched = True
                lane.lane_index = match.lane_index
                lane.lane_id = match.lane.lane_id
                lane.road_id = match.lane.road_id
                lane.station_m = match.station_m
                lane.lateral_offset_m = match.lateral_offset_m
                lane.heading_error_rad = match.heading_error_rad
                lane.lane_width_m = match.lane.width_m
                lane.curvature_1pm = match.curvature_1pm
        return state

    def _without_position(self, state: ego_pb2.EgoState, book: Bookkeeping) -> ego_pb2.EgoState:
        """No fix yet: no position (LOST, no covariance: x, y and heading mean nothing), but the car's own
        latest speed and yaw rate, which need no fix. (position_std_m stays 0, not infinite: consumers that
        ignore the mode would turn an infinite one into NaN covariances.)"""
        state.mode = ego_pb2.LOCALISATION_MODE_LOST
        if book.last_speed_mps is not None or book.last_yaw_rate_radps is not None:
            state.speed_mps = book.last_speed_mps or 0.0
            state.yaw_rate_radps = book.last_yaw_rate_radps or 0.0
        return state


def position_std_m_of(P: np.ndarray) -> float:
    """The position's std along its worst direction."""
    return math.sqrt(max(float(np.linalg.eigvalsh(P[:2, :2])[-1]), 0.0))
