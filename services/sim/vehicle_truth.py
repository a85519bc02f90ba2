"""Ground truth of a simulated vehicle: its model state placed on the road (lane, station, lateral offset)."""
from __future__ import annotations

from typing import Sequence

from coopdrive.services.sim.profiles import VehicleProfile
from coopdrive.services.sim.road_geometry import LaneGeometry, match_lane
from coopdrive.services.sim.vehicle_model import VehicleState
from coopdrive.v1 import sim_pb2

NO_LANE = -1


def vehicle_truth(vehicle_id: str, station_id: int, state: VehicleState, profile: VehicleProfile,
                  lanes: Sequence[LaneGeometry], automated: bool = True) -> sim_pb2.VehicleTruth:
    """A VehicleTruth at the rear axle; lane_index is -1 off every lane in the driving direction."""
    truth = sim_pb2.VehicleTruth(
        vehicle_id=vehicle_id, station_id=station_id, x_m=state.x_m, y_m=state.y_m,
        heading_rad=state.heading_rad, speed_mps=state.speed_mps, accel_mps2=state.accel_mps2,
        yaw_rate_radps=state.yaw_rate_radps, length_m=profile.length_m, width_m=profile.width_m,
        steering_angle_rad=state.steer_rad, automated=automated, lane_index=NO_LANE)
    matched = match_lane(lanes, state.x_m, state.y_m, state.heading_rad)
    if matched is not None:
        lane, truth.station_m, truth.lateral_offset_m = matched
        truth.lane_index = lane.lane_index
        truth.road_id = getattr(lane, "road_id", "")
    return truth
