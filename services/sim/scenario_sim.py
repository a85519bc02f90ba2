"""ScenarioSim: the world of a scenario file, stepped by the simulator service (pure logic, no bus).

Stack vehicles move only by their ACT_ commands (through VehicleModel); stack-role vehicles without a stack
in this run drive their speed profile as scripted vehicles; scripted participants, roadside units, the radio
channel's faults and the sensor suites come from scenario_builder. Ground truth is kept at the judging rate
so the run's metrics are those `coopdrive score` computes from the recording.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

from coopdrive.services.sim.lane_keeping_driver import LaneKeepingDriver
from coopdrive.services.sim.participants import MessageIntent
from coopdrive.services.sim.scenario_builder import RoadMapLike, ScenarioObjects, build_scenario
from coopdrive.services.sim.scenario_config import ScenarioConfig, VehicleRole
from coopdrive.services.sim.sensor_suite import SensorOutputs
from coopdrive.services.sim.signal_rsu import SignalBroadcaster
from coopdrive.services.sim.station_faults import StationFaults
from coopdrive.services.sim.sumo_traffic import SumoTraffic, sumo_traffic_of
from coopdrive.services.sim.vehicle_model import VehicleModel, VehicleState
from coopdrive.services.sim.vehicle_truth import vehicle_truth
from coopdrive.services.sim.world_view import world_views
from coopdrive.v1 import sim_pb2


@dataclass
class StackCommand:
    """What the latest ACT_ frames of a stack vehicle ask for."""

    accel_request_mps2: float | None = None  # None: the driver holds the speed
    steering_request_rad: float | None = None  # None: the driver keeps the lane


class ScenarioSim:
    def __init__(self, config: ScenarioConfig, road_map: RoadMapLike, stack_ids: Sequence[str],
                 already_delayed_steps: int = 0):
        unknown = set(stack_ids) - {v.vehicle_id for v in config.vehicles if v.role is VehicleRole.STACK}
        if unknown:
            raise ValueError(f"stacks: {', '.join(sorted(unknown))} are not stack vehicles of {config.name}")
        # Stack vehicles that run no stack here stay out of the run: scripted, they would drive on blindly
        # into the stacks ahead of them.
        vehicles = [v for v in config.vehicles if v.role is not VehicleRole.STACK or v.vehicle_id in stack_ids]
        kept = {v.vehicle_id for v in vehicles}
        judging = config.judging.model_copy(update={"platoon": [v for v in config.judging.platoon if v in kept]})
        faults = [f for f in config.faults if getattr(f, "vehicle_id", None) in (None, *kept)]
        self.config = config.model_copy(update={"vehicles": vehicles, "judging": judging, "faults": faults})
        self.objects: ScenarioObjects = build_scenario(self.config, road_map)
        self.stack_ids = list(stack_ids)
        # Lockstep already delays each command by up to this many steps: the actuator's own dead time is
        # shortened, by as many whole steps as every stack vehicle's dead times hold (pipelined_steps).
        self.pipelined_steps = max(0, min([already_delayed_steps] + [
            math.floor(min(model.profile.response_dead_time_s, model.profile.steer_dead_time_s) / config.step_s + 1e-9)
            for model in self.objects.models.values()]))
        delay_s = self.pipelined_steps * config.step_s
        for vehicle_id, model in self.objects.models.items():
            profile = model.profile.model_copy(update={
                "response_dead_time_s": max(0.0, model.profile.response_dead_time_s - delay_s),
                "steer_dead_time_s": max(0.0, model.profile.steer_dead_time_s - delay_s)})
            self.objects.models[vehicle_id] = VehicleModel(profile, config.step_s, model.state)
        self.commands = {vehicle_id: StackCommand() for vehicle_id in self.stack_ids}
        self.drivers = {vehicle_id: LaneKeepingDriver(self.objects.lanes[vehicle_id], model.profile.wheelbase_m)
                        for vehicle_id, model in self.objects.models.items()}
        self._config_of = {v.vehicle_id: v for v in vehicles}
        self.station_faults = StationFaults(self.config.faults)
        self.time_s = 0.0
        # Sensors, radio and judge all look at the world between two steps: match lanes once per step.
        self._truths: list[sim_pb2.VehicleTruth] | None = None
        # A modelled vehicle's truth with the state it was made from: the scripted participants step after the
        # models, and the world's truths are taken again then, while most models have not moved since.
        self._model_truths: dict[str, tuple[VehicleState, sim_pb2.VehicleTruth]] = {}
        self.traffic: SumoTraffic | None = None
        if self.config.sumo_traffic is not None:
            edges = {vehicle_id: lanes[0].road_id for vehicle_id, lanes in self.objects.lanes.items()}
            self.traffic = sumo_traffic_of(self.config.sumo_traffic, self.config.map, road_map, self.config.seed,
                                           config.step_s, edges)

    # ----- stepping ---------------------------------------------------------------------------
    def apply_command(self, vehicle_id: str, command: StackCommand) -> None:
        self.commands[vehicle_id] = command

    def step(self, now_s: float) -> None:
        """Moves the world from the previous step to now_s."""
        for vehicle_id, model in self.objects.models.items():
            command = self.commands[vehicle_id]
            state = model.state
            accel = command.accel_request_mps2
            if accel is None:
                accel = model.resistance_mps2(state.speed_mps)  # the driver holds the speed
            steering = command.steering_request_rad
            if steering is None:
                steering = self.drivers[vehicle_id].steering_rad(state)
            model.step(accel, steering)
        self._truths = None
        before = self.truths()
        for participant in self.objects.participants.values():
            participant.step(now_s, before)
        self._truths = None
        if self.traffic is not None:
            self.traffic.step(now_s, self._current_truths(with_traffic=False))
            self._truths = None
        active = self.objects.faults.active(now_s)
        for unit in self.objects.roadside_units:
            if unit.signals is not None:
                unit.signals.set_faults([f for f in active if getattr(f, "unit_id", None) == unit.unit_id])
                unit.signals.step(now_s, self.truths())
        self.objects.faults.update(now_s, self.objects.sensor_suites, self.objects.channel)
        self.time_s = now_s

    # ----- what the world shows -----------------------------------------------------------------
    def truths(self) -> list[sim_pb2.VehicleTruth]:
        """Every vehicle as it stands now (shared messages: read, do not modify)."""
        if self._truths is None:
            self._truths = self._current_truths()
        return list(self._truths)

    def _current_truths(self, with_traffic: bool = True) -> list[sim_pb2.VehicleTruth]:
        """Ours (the scenario's vehicles) first, then SUMO's."""
        truths = []
        for vehicle in self.config.vehicles:
            vehicle_id = vehicle.vehicle_id
            if vehicle_id in self.objects.models:
                model = self.objects.models[vehicle_id]
                made = self._model_truths.get(vehicle_id)
                if made is None or made[0] is not model.state:
                    made = model.state, vehicle_truth(vehicle_id, vehicle.station_id, model.state, model.profile,
                                                      self.objects.lanes[vehicle_id], automated=True)
                    self._model_truths[vehicle_id] = made
                truths.append(made[1])
            else:
                truths.append(self.objects.participants[vehicle_id].truth())
        if with_traffic and self.traffic is not None:
            truths.extend(self.traffic.truths())
        return truths

    def signals(self) -> list[SignalBroadcaster]:
        """The signalised intersections' roadside units' signal parts."""
        return [unit.signals for unit in self.objects.roadside_units if unit.signals is not None]

    def ground_truth(self, collisions: int = 0) -> sim_pb2.GroundTruth:
        signals = [truth for unit in self.signals() for truth in unit.signal_truths(self.time_s)]
        return sim_pb2.GroundTruth(vehicles=self.truths(), collisions=collisions, signals=signals)

    def sensor_outputs(self, now_s: float) -> dict[str, SensorOutputs]:
        truths = self.truths()
        classes = {vid: p.object_class for vid, p in self.objects.participants.items()}
        if self.traffic is not None:
            classes.update(self.traffic.object_classes())
        egos = [truth for truth in truths if truth.vehicle_id in self.objects.sensor_suites]
        outputs = {}
        for view in world_views(truths, egos, classes):
            vehicle_id = view.ego.vehicle_id
            outputs[vehicle_id] = self.objects.sensor_suites[vehicle_id].poll(
                now_s, view, self.objects.models[vehicle_id].brake_pressure_bar())
        return outputs

    def intents(self, now_s: float) -> list[MessageIntent]:
        """What the scripted participants, roadside units and SUMO's equipped vehicles broadcast now."""
        intents = []
        for participant in self.objects.participants.values():
            intents.extend(participant.messages_due(now_s))
        for unit in self.objects.roadside_units:
            intents.extend(unit.messages_due(now_s))
        if self.traffic is not None:
            intents.extend(self.traffic.messages_due(now_s))
        return self.station_faults.apply(intents, now_s, self.truths())

    def radio_positions(self) -> dict[str, tuple[float, float]]:
        positions = {t.vehicle_id: (t.x_m, t.y_m) for t in self.truths()}
        for unit in self.objects.roadside_units:
            positions[unit.unit_id] = (unit.x_m, unit.y_m)
        positions.update(self.station_faults.positions(self.time_s, self.truths()))
        return positions

    def traffic_metrics(self) -> dict[str, float]:
        """SUMO's figures of its vehicles in the run (none without SUMO traffic), and how many of them the stacks'
        cameras detected or radars tracked (sumo_vehicles_seen)."""
        if self.traffic is None:
            return {}
        seen = set().union(*(suite.seen_vehicle_ids() for suite in self.objects.sensor_suites.values()))
        return {**self.traffic.metrics(), "sumo_vehicles_seen": float(len(seen & self.traffic.vehicle_ids()))}

    def close(self) -> None:
        """Ends SUMO's simulation, if the run has one (libsumo holds one per process)."""
        if self.traffic is not None:
            self.traffic.close()
            self.traffic = None

    def finished_early(self) -> str | None:
        """A reason to end the run before its duration (none yet: runs last their duration)."""
        return None

    @staticmethod
    def stopped(truth: sim_pb2.VehicleTruth) -> bool:
        return truth.speed_mps < 0.1 and math.isfinite(truth.speed_mps)
