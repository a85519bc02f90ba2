"""SumoTraffic: SUMO's vehicles driving among ours, stepped in lockstep with the simulator through libsumo.

Our vehicles (stacks and scripted ones) keep our own dynamics: every step each is mirrored into SUMO where it
stands (vehicle.moveToXY, its front bumper, SUMO's reference point), as a vehicle SUMO does not drive (speed mode 0,
lane change mode 0) with its own length and width, so that SUMO's drivers brake, yield and change lanes around it.
Then SUMO steps to the same instant, and its own vehicles become VehicleTruths at their rear axles in our frame
(SumoFrame), with their SUMO type's length and width.

SUMO runs in this process (libsumo: one simulation per process); its seed is the run's seed.
"""

from __future__ import annotations

import math
import os
import random
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from coopdrive.messages.vehicle_frame import rear_overhang_m
from coopdrive.roadmap.sumo_frame import SumoFrame
from coopdrive.services.sim.participants import IntentKind, MessageIntent, RateGate, cam_fields_of
from coopdrive.services.sim.road_geometry import LaneGeometry
from coopdrive.services.sim.sumo_traffic_config import SumoTrafficConfig
from coopdrive.services.sim.vehicle_truth import NO_LANE
from coopdrive.v1 import sensors_pb2, sim_pb2

# SUMO's vehicles get station ids from here on, in the order they appear.
FIRST_SUMO_STATION_ID = 900_000
# moveToXY's keepRoute: 2 places the vehicle on whichever lane is nearest, off its route too.
ANYWHERE = 2
# SUMO's vehicle classes that our sensors class as trucks or emergency vehicles; any other is a car.
TRUCK_CLASSES = {"truck", "trailer", "bus", "coach", "delivery"}
EMERGENCY_CLASSES = {"emergency", "authority"}
# SUMO's statistics, cumulative over the run (simulation.getParameter("", key)), and the metric each becomes.
SUMO_STATISTICS = {"stats.safety.emergencyBraking": "sumo_emergency_braking",
                   "stats.safety.emergencyStops": "sumo_emergency_stops",
                   "stats.safety.collisions": "sumo_collisions",
                   "stats.teleports.total": "sumo_teleports"}


def _libsumo():
    # SUMO validates its XML inputs against the schemas of its installation (the eclipse-sumo package).
    if "SUMO_HOME" not in os.environ:
        import sumo
        os.environ["SUMO_HOME"] = sumo.SUMO_HOME
    import libsumo
    return libsumo


def sumo_heading_rad(angle_deg: float) -> float:
    """Our heading (ENU yaw, counter-clockwise from east) of SUMO's angle (degrees clockwise from north)."""
    return math.remainder(math.radians(90.0 - angle_deg), math.tau)


def sumo_angle_deg(heading_rad: float) -> float:
    return (90.0 - math.degrees(heading_rad)) % 360.0


def front_bumper_xy(x_m: float, y_m: float, heading_rad: float, length_m: float) -> tuple[float, float]:
    """A vehicle's front bumper centre (SUMO's position) of its rear axle (ours)."""
    ahead_m = length_m - rear_overhang_m(length_m)
    return x_m + ahead_m * math.cos(heading_rad), y_m + ahead_m * math.sin(heading_rad)


def rear_axle_xy(x_m: float, y_m: float, heading_rad: float, length_m: float) -> tuple[float, float]:
    ahead_m = length_m - rear_overhang_m(length_m)
    return x_m - ahead_m * math.cos(heading_rad), y_m - ahead_m * math.sin(heading_rad)


class SumoTraffic:
    def __init__(self, traffic: SumoTrafficConfig, network_path: str, frame: SumoFrame, seed: int, step_s: float,
                 lanes: Mapping[str, LaneGeometry], our_edges: Mapping[str, str]) -> None:
        """lanes: our map's lanes by their ids (SUMO's lane ids); our_edges: each of our vehicles' SUMO edge."""
        self.frame = frame
        self.step_s = step_s
        self._lanes = lanes
        self._our_edges = dict(our_edges)
        self._mirrored: set[str] = set()
        self._station_ids: dict[str, int] = {}
        self._classes: dict[str, int] = {}
        self._last_heading: dict[str, float] = {}
        self._truths: list[sim_pb2.VehicleTruth] = []
        self._seed = seed
        self._equipped_share = traffic.equipped_share
        self._cam_rate_hz = traffic.cam_rate_hz
        # The equipped vehicles' CAM timing, each from when it first drove in our world.
        self._cam_gates: dict[str, RateGate] = {}
        self.time_s = 0.0
        # (collider, victim) pairs SUMO saw collide, one of them ours: a lasting contact counts once.
        self._contacts_with_ours: set[tuple[str, str]] = set()
        self.sumo = _libsumo()
        self.sumo.start(["sumo", *self._inputs(traffic, network_path), "--seed", str(seed),
                         "--step-length", f"{step_s:.6g}", "--begin", "0", "--no-step-log", "true",
                         "--collision.action", traffic.collision_action, "--collision.check-junctions", "true"])

    @staticmethod
    def _inputs(traffic: SumoTrafficConfig, network_path: str) -> list[str]:
        if traffic.config is not None:
            return ["--configuration-file", traffic.config, "--net-file", network_path]
        return ["--net-file", network_path, "--route-files", ",".join(traffic.routes)]

    # ----- stepping ---------------------------------------------------------------------------
    def step(self, now_s: float, ours: Sequence[sim_pb2.VehicleTruth]) -> None:
        """Our vehicles where they stand at now_s into SUMO, then SUMO to now_s."""
        for truth in ours:
            self._mirror(truth)
        self.sumo.simulationStep(now_s)
        self.time_s = now_s
        for vehicle_id in self.sumo.simulation.getArrivedIDList():
            self._mirrored.discard(vehicle_id)
        self._contacts_with_ours.update((c.collider, c.victim) for c in self.sumo.simulation.getCollisions()
                                        if c.collider in self._our_edges or c.victim in self._our_edges)
        theirs = [vehicle_id for vehicle_id in self.sumo.vehicle.getIDList() if vehicle_id not in self._our_edges]
        fronts = self.frame.to_local_many(np.array([self.sumo.vehicle.getPosition(vehicle_id) for vehicle_id in theirs],
                                                   dtype=float).reshape(-1, 2))
        self._truths = [self._truth_of(vehicle_id, front) for vehicle_id, front in zip(theirs, fronts)]

    def _mirror(self, truth: sim_pb2.VehicleTruth) -> None:
        vehicle = self.sumo.vehicle
        if truth.vehicle_id not in self._mirrored:
            route_id = f"coopdrive:{truth.vehicle_id}"
            if route_id not in self.sumo.route.getIDList():
                self.sumo.route.add(route_id, [self._our_edges[truth.vehicle_id]])
            vehicle.add(truth.vehicle_id, route_id, depart="now", departSpeed=f"{truth.speed_mps:.3f}")
            vehicle.setLength(truth.vehicle_id, truth.length_m)
            vehicle.setWidth(truth.vehicle_id, truth.width_m)
            vehicle.setSpeedMode(truth.vehicle_id, 0)
            vehicle.setLaneChangeMode(truth.vehicle_id, 0)
            self._mirrored.add(truth.vehicle_id)
        x_m, y_m = self.frame.to_network(*front_bumper_xy(truth.x_m, truth.y_m, truth.heading_rad, truth.length_m))
        vehicle.moveToXY(truth.vehicle_id, "", -1, x_m, y_m, sumo_angle_deg(truth.heading_rad), ANYWHERE)
        vehicle.setSpeed(truth.vehicle_id, max(0.0, truth.speed_mps))

    # ----- what SUMO's vehicles show ------------------------------------------------------------
    def truths(self) -> list[sim_pb2.VehicleTruth]:
        return list(self._truths)

    def vehicle_ids(self) -> set[str]:
        """SUMO's vehicles that have driven in our world so far."""
        return set(self._station_ids)

    def object_classes(self) -> dict[str, int]:
        return dict(self._classes)

    def _truth_of(self, vehicle_id: str, front_xy: np.ndarray) -> sim_pb2.VehicleTruth:
        """The vehicle's truth, its front bumper (SUMO's position) at front_xy in our frame."""
        vehicle = self.sumo.vehicle
        length_m, width_m = vehicle.getLength(vehicle_id), vehicle.getWidth(vehicle_id)
        heading = sumo_heading_rad(vehicle.getAngle(vehicle_id))
        x_m, y_m = rear_axle_xy(float(front_xy[0]), float(front_xy[1]), heading, length_m)
        last = self._last_heading.get(vehicle_id)
        self._last_heading[vehicle_id] = heading
        truth = sim_pb2.VehicleTruth(
            vehicle_id=vehicle_id, station_id=self._station_id(vehicle_id), x_m=x_m, y_m=y_m, heading_rad=heading,
            speed_mps=vehicle.getSpeed(vehicle_id), accel_mps2=vehicle.getAcceleration(vehicle_id),
            yaw_rate_radps=0.0 if last is None else math.remainder(heading - last, math.tau) / self.step_s,
            length_m=length_m, width_m=width_m, automated=False, lane_index=NO_LANE)
        # On the lane SUMO drives it on, if that is one of ours (not a junction's internal lane).
        lane = self._lanes.get(vehicle.getLaneID(vehicle_id))
        if lane is not None:
            truth.station_m, truth.lateral_offset_m = lane.project(x_m, y_m)[:2]
            truth.lane_index = lane.lane_index
            truth.road_id = lane.road_id
        return truth

    def _station_id(self, vehicle_id: str) -> int:
        if vehicle_id not in self._station_ids:
            self._station_ids[vehicle_id] = FIRST_SUMO_STATION_ID + len(self._station_ids)
            self._classes[vehicle_id] = _object_class(self.sumo.vehicle.getVehicleClass(vehicle_id))
            if random.Random(f"{self._seed}/{vehicle_id}").random() < self._equipped_share:
                self._cam_gates[vehicle_id] = RateGate(self._cam_rate_hz, self.time_s)
        return self._station_ids[vehicle_id]

    def messages_due(self, now_s: float) -> list[MessageIntent]:
        """The CAMs the equipped vehicles send now: their truth, as a scripted vehicle's CAM in the ideal world."""
        return [MessageIntent(IntentKind.CAM, t.vehicle_id, t.station_id, now_s, cam_fields_of(t)) for t in self._truths
                if t.vehicle_id in self._cam_gates and self._cam_gates[t.vehicle_id].due(now_s)]

    # ----- the run's figures ---------------------------------------------------------------------
    def metrics(self) -> dict[str, float]:
        """SUMO's vehicles that drove in our world, and SUMO's own count of their emergency braking, emergency
        stops, collisions (theirs among themselves and with ours) and teleports; collisions SUMO saw with ours."""
        figures = {"sumo_vehicles": float(len(self._station_ids)), "sumo_equipped": float(len(self._cam_gates)),
                   "sumo_collisions_with_ours": float(len(self._contacts_with_ours))}
        for key, name in SUMO_STATISTICS.items():
            figures[name] = float(self.sumo.simulation.getParameter("", key))
        return figures

    def close(self) -> None:
        self.sumo.close()


def _object_class(vehicle_class: str) -> int:
    if vehicle_class in EMERGENCY_CLASSES:
        return sensors_pb2.OBJECT_CLASS_EMERGENCY_VEHICLE
    if vehicle_class in TRUCK_CLASSES:
        return sensors_pb2.OBJECT_CLASS_TRUCK
    return sensors_pb2.OBJECT_CLASS_CAR


def sumo_traffic_of(traffic: SumoTrafficConfig, network_path: str, road_map, seed: int, step_s: float,
                    our_edges: Mapping[str, str]) -> SumoTraffic:
    """SumoTraffic on the scenario's network, laid in the frame its road map was read in."""
    frame = SumoFrame.of_network(Path(network_path), road_map)
    lanes = {lane.lane_id: lane for lane in road_map.lanes}
    return SumoTraffic(traffic, network_path, frame, seed, step_s, lanes, our_edges)
