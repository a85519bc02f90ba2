"""Every packaged scenario keeps its stack cars on the roads of its map for the whole run."""

import numpy as np
import pytest

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.config import packaged_scenario_file
from coopdrive.services.sim.scenario_config import VehicleRole, load_scenario

SCENARIOS = ["follow", "string", "merge", "platoon40", "emergency", "intersection", "localisation", "signals",
             "sumo-motorway"]


def fastest_scripted_mps(vehicle, duration_s: float) -> float:
    if vehicle.speed_profile is None:
        return vehicle.speed_mps
    return max(vehicle.speed_profile.speed_at(float(t)) for t in np.arange(0.0, duration_s + 0.5, 0.5))


@pytest.mark.parametrize("name", SCENARIOS)
def test_no_stack_car_of_the_scenario_runs_off_the_end_of_its_lane(name):
    """A stack car drives at most as fast as the scripted cars of its road (it follows them) or, with none there, at
    the speed limit."""
    scenario = load_scenario(packaged_scenario_file(name))
    road_map = RoadMap.load(scenario.map)

    def road_of(vehicle):
        return vehicle.road or road_map.lanes[0].road_id

    for vehicle in scenario.vehicles:
        if vehicle.role is not VehicleRole.STACK:
            continue
        (lane,) = [lane for lane in road_map.lanes_of_road(road_of(vehicle)) if lane.lane_index == vehicle.lane]
        scripted = [fastest_scripted_mps(other, scenario.duration_s) for other in scenario.vehicles
                    if other.role is not VehicleRole.STACK and road_of(other) == road_of(vehicle)]
        fastest_mps = max(scripted) if scripted else lane.speed_limit_mps
        assert vehicle.station_m + fastest_mps * scenario.duration_s <= lane.length_m, vehicle.vehicle_id
