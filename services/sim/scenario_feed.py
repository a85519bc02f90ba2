"""ScenarioFeed: the simulator service's side of a scenario-file run.

It steps ScenarioSim every simulation step, publishes each stack vehicle's sensor outputs on that vehicle's
topics, plays the radio boxes (RadioBox) between the stacks' v2x services, publishes ground truth, and at
the end the RunResult with the judge's metrics. SimService wires it; the world logic stays in ScenarioSim.
"""

from __future__ import annotations

import functools
import time


from coopdrive.bus import Envelope
from coopdrive.bus.keys import WORLD_ID
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.frames import CanDecodeError
from coopdrive.roadmap import RoadMap
from coopdrive.runtime.service import Service
from coopdrive.services.sim.fault_config import CanErrorBurst
from coopdrive.services.sim.gnss_pty import GnssPty
from coopdrive.services.sim.intent_encoder import IntentEncoder
from coopdrive.services.sim.radio_faults import RadioFaults
from coopdrive.services.sim.sender_signing import SenderSigning
from coopdrive.services.sim.mission_verdict import MissionJudge
from coopdrive.services.sim.radio_box import RadioBox, RadioPorts
from coopdrive.services.sim.scenario_config import load_scenario
from coopdrive.services.sim.world_profile import WorldProfile
from coopdrive.services.sim.scenario_sim import ScenarioSim, StackCommand
from coopdrive.services.sim.vehicle_bus_writer import VehicleBusWriter
from coopdrive.v1 import sim_pb2

# SensorOutputs field -> the stack topic it is published on; can_state, imu and radar go on the CAN bus
# (can/vehicle).
SENSOR_TOPICS = {"gnss": "gnss/fix", "lidar": "lidar/scan", "camera": "camera/frame", "sonar": "sonar/ranges"}
GROUND_TRUTH_PERIOD_S = 0.1


class ScenarioFeed:
    def __init__(self, service: Service, scenario_file: str, stacks: list[str], radio_links: dict[str, dict],
                 already_delayed_steps: int, gnss_ports: dict[str, str] | None = None):
        self.service = service
        self.ctx = service.ctx
        # The run's seed (`coopdrive run --seed`) draws the noise, losses and dropouts, not the file's default.
        config = load_scenario(scenario_file).model_copy(update={"seed": service.config.seed}).in_world(
            WorldProfile(service.config.world_profile))
        self.road_map = RoadMap.load(config.map)
        self.stacks = stacks or [v.vehicle_id for v in config.vehicles if v.role.value == "stack"]
        self.sim = ScenarioSim(config, self.road_map, self.stacks, already_delayed_steps)
        self.config = self.sim.config
        self.codecs = {vehicle_id: VehicleCanCodec() for vehicle_id in self.stacks}
        self.vehicle_buses = {vehicle_id: VehicleBusWriter() for vehicle_id in self.stacks}
        self.box = RadioBox({v: RadioPorts(**ports) for v, ports in radio_links.items()}, self.sim.objects.channel)
        self.encoder = IntentEncoder(self.road_map.to_geodetic, config.utc_epoch)
        pki_dir = service.config.security_pki_dir
        self.signing = SenderSigning(pki_dir, config.utc_epoch) if pki_dir else None
        self.radio_faults = RadioFaults(self.config.faults, self.signing.unsecured if self.signing else None)
        self.judge = MissionJudge(self.config, self.stacks)
        self.finished = False
        # Vehicles whose GNSS receiver talks NMEA over a serial line; the others get gnss/fix on the bus.
        self.gnss_lines = {vehicle_id: GnssPty(path) for vehicle_id, path in (gnss_ports or {}).items()}
        for vehicle_id in self.stacks:
            self.ctx.subscribe("can/command", self.on_can_command, vehicle_id=vehicle_id)
            if vehicle_id in radio_links:
                self.ctx.subscribe("v2x/tx", self.on_v2x_transmitted, vehicle_id=vehicle_id)
        self.ctx.every(config.step_s, self.on_step)
        self.ctx.every(GROUND_TRUTH_PERIOD_S, self.publish_ground_truth)

    # ----- inputs -----------------------------------------------------------------------------
    def on_can_command(self, envelope: Envelope) -> None:
        try:
            command = self.codecs[envelope.vehicle_id].decode_command_frame(envelope.message)
        except CanDecodeError as error:
            self.service.count("rejected_can_commands")
            if self.service.counters["rejected_can_commands"] == 1:
                self.ctx.log.warning("rejected a CAN command frame from %s: %s", envelope.vehicle_id, error)
            return
        self.judge.observe_automation(envelope.vehicle_id, command.longitudinal_active, self.ctx.now_s())
        # When actuation sent it, not when the (feedback-delayed) world applies it.
        self.judge.observe_mode(envelope.vehicle_id, command.driving_mode, envelope.message.header.sample_time_s)
        model = self.sim.objects.models[envelope.vehicle_id]
        accel = model.command_to_accel_mps2(command.throttle_ratio, command.brake_ratio,
                                            command.deceleration_request_mps2) if command.longitudinal_active else None
        steering = command.steering_angle_request_rad if command.lateral_active else None
        self.sim.apply_command(envelope.vehicle_id, StackCommand(accel, steering))

    def on_v2x_transmitted(self, envelope: Envelope) -> None:
        self.box.on_transmitted(envelope.vehicle_id, envelope.message.payload)

    # ----- time triggers ------------------------------------------------------------------------
    def on_step(self, now_s: float) -> None:
        if now_s > 0:
            self.sim.step(now_s)
        for vehicle_id, outputs in self.sim.sensor_outputs(now_s).items():
            line = self.gnss_lines.get(vehicle_id)
            for field_name, topic in SENSOR_TOPICS.items():
                for item in getattr(outputs, field_name):
                    # Stamped with when the sensor sampled the world, as a time-synchronised LiDAR or camera stamps
                    # its data; the runtime would otherwise put the delivery time there, and the sensor's latency
                    # would become an error the stack cannot know of (a car passing at 20 m/s: 0.8 m behind).
                    if field_name != "gnss":
                        self.ctx.publish_for(vehicle_id, topic, item, sample_time_s=item.header.sample_time_s)
                    elif line is None:
                        self.ctx.publish_for(vehicle_id, topic, item.message, sample_time_s=item.sample_time_s)
                    else:
                        self.ctx.publish_for(vehicle_id, "gnss/serial_mark",
                                             sim_pb2.WireMark(written=line.write(item.data)))
            frames = self.vehicle_buses[vehicle_id].frames(now_s, self.config.step_s, outputs.can_state, outputs.radar,
                                                           outputs.imu, self._error_frames_per_s(vehicle_id, now_s))
            if frames is not None:
                self.ctx.publish_for(vehicle_id, "can/vehicle", frames)
        for intent in self.sim.intents(now_s):
            packet = self.encoder.encode(intent)
            if packet is not None:
                # A ghost (a station that does not exist) holds no ticket of the run's PKI: it sends unsigned.
                if self.signing is not None and self.signing.holds_ticket(intent.sender_id):
                    packet = self.signing.seal(intent, packet)
                self.box.broadcast(intent.sender_id, packet)
        on_air = functools.partial(self.radio_faults.keeps, now_s=now_s)
        for vehicle_id, written in self.box.step(now_s, self.sim.radio_positions(), on_air).items():
            self.ctx.publish_for(vehicle_id, "radio/mark", sim_pb2.WireMark(written=written))
        self.service.counters["radio_missing"] = self.box.stats.missing
        self.service.counters["radio_mismatched"] = self.box.stats.mismatched
        self.service.counters["radio_fault_silenced"] = self.radio_faults.silenced_count
        self.service.counters["radio_fault_dropped_iclcm"] = self.radio_faults.dropped_count
        if now_s >= self.service.config.duration_s - 1e-9 and not self.finished:
            self.finish(now_s)

    def _error_frames_per_s(self, vehicle_id: str, now_s: float) -> float:
        return sum(fault.error_frames_per_s for fault in self.sim.objects.faults.active(now_s)
                   if isinstance(fault, CanErrorBurst) and fault.vehicle_id == vehicle_id)

    def publish_ground_truth(self, now_s: float) -> None:
        truth = self.sim.ground_truth()
        self.judge.observe(now_s, truth)
        truth.collisions = self.judge.collisions
        self.ctx.publish_for(WORLD_ID, "ground_truth", truth)

    def finish(self, now_s: float) -> None:
        self.finished = True
        success, reason = self.judge.verdict()
        result = sim_pb2.RunResult(scenario=self.config.name, seed=self.service.config.seed, success=success,
                                   failure_reason=reason, sim_time_s=now_s,
                                   wall_time_s=time.monotonic() - self.service.wall_start_s,
                                   clock_started_monotonic_s=self.service.wall_start_s)
        for key, value in self.judge.metrics().items():
            result.metrics[key] = value
        result.fault_reactions.extend(reaction.describe() for reaction in self.judge.fault_reactions())
        for key, value in self.sim.traffic_metrics().items():
            result.metrics[key] = value
        for counter in ("participants_lost", "service_crashes", "service_restarts"):
            result.metrics[counter] = self.service.counters.get(counter, 0)
        self.ctx.publish_for(WORLD_ID, "result", result)
        self.ctx.request_stop("scenario finished")

    def close(self) -> None:
        self.sim.close()
        self.box.close()
        for line in self.gnss_lines.values():
            line.close()
