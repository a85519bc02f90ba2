"""Builds the pure-logic objects of a run from a ScenarioConfig and a road map (no processes, no bus)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, Sequence

from coopdrive.services.sim.cam_noise import CamNoise
from coopdrive.services.sim.fault_schedule import FaultSchedule
from coopdrive.services.sim.intersection_map import approach_lane
from coopdrive.services.sim.participants import EmergencyVehicle, ScriptedVehicle
from coopdrive.services.sim.radio_channel import RadioChannel
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.services.sim.roadside_unit import RoadsideUnit
from coopdrive.services.sim.signal_rsu import SignalBroadcaster
from coopdrive.services.sim.scenario_config import RoadsideUnitConfig, ScenarioConfig, VehicleConfig, VehicleRole
from coopdrive.services.sim.sensor_suite import SensorSuite
from coopdrive.services.sim.sensor_timing import sensor_rng
from coopdrive.services.sim.speed_profiles import ConstantSpeed, SpeedProfile
from coopdrive.services.sim.vehicle_model import VehicleModel, VehicleState
from coopdrive.services.sim.world_profile import WorldProfile, ideal

CHANNEL_RNG_NAME = "radio_channel"
# The generator of a scripted vehicle's own GNSS receiver, whose solution its CAMs carry.
CAM_GNSS_RNG_NAME = "cam_gnss"


class RoadMapLike(Protocol):
    """What the builder needs of coopdrive.roadmap.RoadMap."""

    lanes: Sequence[LaneGeometry]

    def lanes_of_road(self, road_id: str) -> list[LaneGeometry]:
        ...

    def to_geodetic(self, x_m: float, y_m: float, z_m: float = 0.0) -> tuple[float, float, float]:
        ...


@dataclass
class ScenarioObjects:
    config: ScenarioConfig
    lanes: dict[str, list[LaneGeometry]]
    # Vehicles running the stack: their dynamics and sensors.
    models: dict[str, VehicleModel]
    sensor_suites: dict[str, SensorSuite]
    # Behaviour objects (scripted and emergency vehicles).
    participants: dict[str, ScriptedVehicle]
    roadside_units: list[RoadsideUnit]
    channel: RadioChannel
    faults: FaultSchedule


def speed_profile_of(vehicle: VehicleConfig) -> SpeedProfile:
    return vehicle.speed_profile or ConstantSpeed(speed_mps=vehicle.speed_mps)


def _road_lanes(road_map: RoadMapLike, vehicle: VehicleConfig) -> list[LaneGeometry]:
    road = vehicle.road or getattr(road_map.lanes[0], "road_id", "")
    lanes = road_map.lanes_of_road(road)
    if not lanes:
        raise ValueError(f"vehicle {vehicle.vehicle_id}: the map has no road {road!r}")
    if vehicle.lane not in {lane.lane_index for lane in lanes}:
        raise ValueError(f"vehicle {vehicle.vehicle_id}: road {road!r} has no lane {vehicle.lane}")
    return lanes


def check_roads(config: ScenarioConfig, road_map: RoadMapLike) -> None:
    """ValueError naming the first vehicle or signal approach on a road or lane the map does not have: what
    build_scenario would refuse, checked before a run starts anything."""
    for vehicle in config.vehicles:
        _road_lanes(road_map, vehicle)
    for unit in config.roadside_units:
        for approach in unit.intersection.approaches if unit.intersection is not None else ():
            approach_lane(road_map.lanes_of_road, approach)


def _signals(config: ScenarioConfig, unit: RoadsideUnitConfig, road_map: RoadMapLike) -> SignalBroadcaster | None:
    if unit.intersection is None:
        return None
    return SignalBroadcaster(unit.intersection, unit.station_id, road_map.lanes_of_road, road_map.to_geodetic,
                             config.utc_epoch)


def build_scenario(config: ScenarioConfig, road_map: RoadMapLike) -> ScenarioObjects:
    """Raises ValueError naming the vehicle when its road or lane is not in the map."""
    lanes: dict[str, list[LaneGeometry]] = {}
    models: dict[str, VehicleModel] = {}
    suites: dict[str, SensorSuite] = {}
    participants: dict[str, ScriptedVehicle] = {}
    for vehicle in config.vehicles:
        road_lanes = _road_lanes(road_map, vehicle)
        lanes[vehicle.vehicle_id] = road_lanes
        real = config.world is WorldProfile.REAL
        profile = vehicle.plant_profile() if real else ideal(vehicle.plant_profile())
        if vehicle.role is VehicleRole.STACK:
            lane = next(lane for lane in road_lanes if lane.lane_index == vehicle.lane)
            x_m, y_m, heading = lane.pose_at(vehicle.station_m, vehicle.lateral_offset_m)
            state = VehicleState(x_m=x_m, y_m=y_m, heading_rad=heading, speed_mps=vehicle.speed_mps)
            models[vehicle.vehicle_id] = VehicleModel(profile, config.step_s, state)
            suites[vehicle.vehicle_id] = SensorSuite(config.sensors_of(vehicle), config.seed, vehicle.vehicle_id,
                                                     profile, road_map.to_geodetic, config.utc_epoch,
                                                     list(road_map.lanes))
            continue
        common = dict(vehicle_id=vehicle.vehicle_id, station_id=vehicle.station_id, profile=profile,
                      lanes=road_lanes, lane_index=vehicle.lane, station_m=vehicle.station_m,
                      speed_profile=speed_profile_of(vehicle), lane_changes=vehicle.lane_changes,
                      lateral_offset_m=vehicle.lateral_offset_m, ignores_protocol=vehicle.ignores_protocol)
        if vehicle.role is VehicleRole.EMERGENCY:
            siren = vehicle.siren
            participants[vehicle.vehicle_id] = EmergencyVehicle(
                **common, siren_on_s=siren.on_s if siren else 0.0,
                siren_off_s=siren.off_s if siren else float("inf"))
        else:
            participants[vehicle.vehicle_id] = ScriptedVehicle(**common)
        if real:
            participants[vehicle.vehicle_id].cam_noise = CamNoise(
                config.sensors_of(vehicle).gnss, sensor_rng(config.seed, vehicle.vehicle_id, CAM_GNSS_RNG_NAME))
    units = [RoadsideUnit(u.unit_id, u.station_id, u.x_m, u.y_m, u.events, u.rate_hz, _signals(config, u, road_map))
             for u in config.roadside_units]
    stop_lines = [line for unit in units if unit.signals is not None for line in unit.signals.stop_lines]
    for participant in participants.values():
        participant.stop_lines = stop_lines
    channel = RadioChannel(config.channel, sensor_rng(config.seed, "", CHANNEL_RNG_NAME))
    return ScenarioObjects(config, lanes, models, suites, participants, units, channel, FaultSchedule(config.faults))
