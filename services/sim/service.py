"""The simulator service: owns simulated time, moves the world, feeds every stack its sensors."""

from __future__ import annotations

import math
import time
from typing import Literal

import numpy as np
import pymap3d
from pydantic import Field

from coopdrive.bus import Envelope
from coopdrive.bus.keys import WORLD_ID
from coopdrive.can.codec import VehicleCanCodec
from coopdrive.can.frames import CanDecodeError
from coopdrive.runtime.master import ClockMaster, ClockSettings
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.services.sim.follow_judge import FollowJudge
from coopdrive.services.sim.profiles import PROFILES, ProfileName
from coopdrive.services.sim.scenario_config import load_scenario
from coopdrive.services.sim.scenario_feed import ScenarioFeed
from coopdrive.services.sim.service_crashes import crash_outages
from coopdrive.services.sim.vehicle_bus_writer import VehicleBusWriter
from coopdrive.services.sim.vehicle_model import VehicleModel
from coopdrive.services.sim.world_config import VehicleSpec, WorldConfig
from coopdrive.services.sim.world_service import FollowWorld
from coopdrive.v1 import gnss_pb2, sensors_pb2, sim_pb2, vehicle_pb2


# In manual mode the simulated driver holds the speed and keeps to the straight lane.
MANUAL_ACCEL_MPS2 = 0.0
MANUAL_STEERING_RAD = 0.0
# Stacks engage at their starting speed; the margin covers the wheel-speed noise.
FLYING_START_MARGIN_MPS = 1.0
# Comfort deceleration of the follow stacks: above the leader's 3 m/s2 braking, within the car's 8 m/s2.
FOLLOW_COMFORT_DECEL_MPS2 = 3.5


def default_follow_world() -> WorldConfig:
    leader_profile = [(0, 15), (10, 15), (16, 22), (28, 22), (32, 10), (42, 10), (50, 15), (60, 15)]
    return WorldConfig(vehicles=[
        VehicleSpec(vehicle_id="leader", station_id=1001, station_m=45.0, speed_profile=leader_profile),
        VehicleSpec(vehicle_id="ego", station_id=1002, station_m=0.0),
    ])


class SimConfig(ServiceConfig):
    scenario: str = "follow"
    seed: int = 1
    duration_s: float = 60.0
    step_s: float = 0.02
    lockstep: bool = True
    # Pace to the wall clock (--realtime); with lockstep the stack still never falls behind.
    paced: bool = False
    realtime_factor: float = 1.0
    participants: list[str] = Field(default_factory=list)
    startup_timeout_s: float = 60.0
    # Lockstep: a command computed in step k moves the vehicle from step k + feedback_delay_steps, which keeps
    # that many steps in flight. The vehicle models take the extra steps off their actuators' dead times, so the
    # physics is the same as with 1; fewer are used when a stack vehicle's dead time is shorter than that.
    feedback_delay_steps: int = Field(default=3, ge=1)
    # Full-throttle and full-brake accelerations the stack vehicles' ACT_ pedal ratios are scaled by.
    pedal_profile: ProfileName = ProfileName.PASSENGER_CAR
    # Spacing policy d = r + h v the run is judged against.
    standstill_m: float = 6.0
    time_gap_s: float = 1.5
    world: WorldConfig = Field(default_factory=default_follow_world)
    # A scenario file (scenarios/*.yaml or a user's own) instead of the built-in follow world.
    scenario_file: str = ""
    # `ideal` runs the scenario in the ideal world (world_profile.py) whatever its file says; `real` keeps the
    # file's own `world` (real unless it says ideal).
    world_profile: Literal["real", "ideal"] = "real"
    # Its vehicles that run a coopdrive stack; empty: every stack vehicle of the file.
    stacks: list[str] = Field(default_factory=list)
    # vehicle_id -> {"box_port", "stack_port"}: the UDP ports of that vehicle's simulated radio box.
    radio_links: dict[str, dict[str, int]] = Field(default_factory=dict)
    # vehicle_id -> path of the link to that vehicle's GNSS serial line (a pty carrying NMEA), instead of gnss/fix.
    gnss_ports: dict[str, str] = Field(default_factory=dict)
    # Secured runs: the test PKI whose tickets the scripted vehicles and roadside units sign with ("": unsigned).
    security_pki_dir: str = ""

    def stack_overrides(self) -> dict[str, dict]:
        """What this world needs in every stack's service configs; the launcher merges its own over them.

        Geolocation: the follow world lies off every lane map, so the world's origin and no lane matching; the
        simulated GNSS antenna sits at the vehicle reference point; the odometry needs the simulated track width
        and wheel-speed noise. Geolocation and scene: the world's CAN state and radar are on the bus in the step
        they were measured, so there is no sender latency to take off. Control: radar-only following at the judged time gap, braking as hard as the
        leader does without an emergency. Actuation: the stacks have no v2x service and start moving, so they
        engage cooperative (longitudinal) control at once, at speed, without the V2X condition (a vehicle's
        default is to wait for its driver, below 10 km/h, with V2X).
        """
        if self.scenario_file:
            return scenario_stack_overrides(self.scenario_file)
        world = self.world
        stacks = [v for v in world.vehicles if not v.speed_profile]
        if not stacks:
            return {}
        # One set of overrides serves every stack, so the first stack vehicle stands for all.
        return {
            "geolocation": {
                "map_name": None,
                "origin": {"lat_deg": world.origin_lat_deg, "lon_deg": world.origin_lon_deg,
                           "alt_m": world.origin_alt_m},
                "geolocator": {"antenna_x_m": 0.0, "antenna_y_m": 0.0, "track_width_m": stacks[0].track_width_m,
                               "wheelbase_m": stacks[0].wheelbase_m,
                               "wheel_speed_std_mps": world.can.wheel_speed_sigma_mps},
                "can_latency_s": 0.0,
            },
            "scene": {"radar_latency_s": 0.0},
            "control": {"profile_overrides": {
                # Nothing to fall back from: without V2X the planner's time gap already is the ACC gap.
                "spacing": {"fallback_time_gap_raise_s": 0.0},
                # The scripted leader brakes at 3 m/s2 for 4 s; below that the comfort limit sends every such
                # braking through the emergency path, which overshoots and leaves the gap open for seconds.
                "limits": {"max_decel_mps2": FOLLOW_COMFORT_DECEL_MPS2},
            }},
            "actuation": {
                "engage_on_start": "cooperative",
                "require_v2x": False,
                "actuator": {"modes": {"max_engage_speed_mps": max(v.speed_mps for v in stacks)
                                       + FLYING_START_MARGIN_MPS}},
            },
        }


def scenario_stack_overrides(scenario_file: str) -> dict[str, dict]:
    """What a scenario file's world needs in every stack: its lane map for geolocation and scene, and
    stacks that engage the scenario's mode (autonomous unless it says cooperative) at once, at speed, as a
    safety driver would at the start."""
    scenario = load_scenario(scenario_file)
    fastest_mps = max((v.speed_mps for v in scenario.vehicles), default=0.0)
    return {
        "geolocation": {"map_name": scenario.map},
        "scene": {"map_name": scenario.map},
        "actuation": {"engage_on_start": scenario.engage.value, "require_v2x": False,
                      "actuator": {"modes": {"max_engage_speed_mps": fastest_mps + FLYING_START_MARGIN_MPS}}},
    }


class SimService(Service, ClockMaster.Driven):
    name = "sim"
    Config = SimConfig

    def start(self) -> None:
        config: SimConfig = self.config
        self.wall_start_s = time.monotonic()
        self.feed = None
        if config.scenario_file:
            self.feed = ScenarioFeed(self, config.scenario_file, config.stacks, config.radio_links,
                                     already_delayed_steps=config.feedback_delay_steps - 1,
                                     gnss_ports=config.gnss_ports)
            return
        self.world = FollowWorld(config.world, config.step_s, already_delayed_steps=config.feedback_delay_steps - 1)
        self.rng = np.random.default_rng(config.seed)
        self.judge = FollowJudge(config.standstill_m, config.time_gap_s)
        self.stack_vehicles = [s.vehicle_id for s in config.world.vehicles if not s.speed_profile]
        self.accel_requests: dict[str, float] = {}
        self.steering_requests: dict[str, float] = {}
        # One codec per vehicle bus (rolling counters are per receiver); the model only maps pedals to a request.
        self.command_codecs = {vehicle_id: VehicleCanCodec() for vehicle_id in self.stack_vehicles}
        self.vehicle_buses = {vehicle_id: VehicleBusWriter() for vehicle_id in self.stack_vehicles}
        self.pedals = VehicleModel(PROFILES[config.pedal_profile], config.step_s)
        self.finished = False
        for vehicle_id in self.stack_vehicles:
            self.ctx.subscribe("can/command", self.on_can_command, vehicle_id=vehicle_id)
        world = config.world
        self.ctx.every(config.step_s, self.on_step)
        self.ctx.every(1.0 / world.can.rate_hz, self.publish_can_state)
        self.ctx.every(1.0 / world.gnss.rate_hz, self.publish_gnss)
        self.ctx.every(1.0 / world.radar.rate_hz, self.publish_radar)
        self.ctx.every(1.0 / world.ground_truth_rate_hz, self.publish_ground_truth)

    def stop(self) -> None:
        if getattr(self, "feed", None) is not None:
            self.feed.close()

    # ----- ClockMaster.Driven ---------------------------------------------------------------
    def clock_settings(self) -> ClockSettings:
        c: SimConfig = self.config
        return ClockSettings(step_s=c.step_s, lockstep=c.lockstep, paced=c.paced, realtime_factor=c.realtime_factor,
                             participants=list(c.participants), startup_timeout_s=c.startup_timeout_s,
                             feedback_delay_steps=1 + self._pipelined_steps() if c.lockstep else 1,
                             outages=crash_outages(self.feed.config.faults, c.participants, c.step_s)
                             if self.feed is not None else [])

    def on_outage(self, participant: str, restart: bool) -> None:
        """Tells the launcher, which owns the processes, to kill the service's process or start it again."""
        self.count("service_restarts" if restart else "service_crashes")
        self.ctx.log.info("service_crash: %s %s at %.2f s", "restarting" if restart else "killing", participant,
                          self.ctx.now_s())
        self.ctx.publish_for(WORLD_ID, "service_fault", sim_pb2.ServiceFault(participant=participant, restart=restart))

    def _pipelined_steps(self) -> int:
        return self.feed.sim.pipelined_steps if self.feed is not None else self.world.pipelined_steps

    def on_clock_started(self, wall_start_monotonic_s: float) -> None:
        self.wall_start_s = wall_start_monotonic_s

    def on_clock_failed(self, reason: str) -> None:
        """The launcher waits for a result: it gets one that says why the run never started."""
        config: SimConfig = self.config
        self.ctx.publish_for(WORLD_ID, "result", sim_pb2.RunResult(
            scenario=config.scenario, seed=config.seed, success=False, failure_reason=f"the run never started: {reason}"))

    # ----- inputs ---------------------------------------------------------------------------
    def on_can_command(self, envelope: Envelope) -> None:
        """An ACT_ frame from a stack's actuation; the latest values of all three are applied every step."""
        try:
            command = self.command_codecs[envelope.vehicle_id].decode_command_frame(envelope.message)
        except CanDecodeError as error:
            self.count("rejected_can_commands")
            if self.counters["rejected_can_commands"] == 1:
                self.ctx.log.warning("rejected a CAN command frame from %s: %s", envelope.vehicle_id, error)
            return
        vehicle_id = envelope.vehicle_id
        if command.longitudinal_active:
            self.accel_requests[vehicle_id] = self.pedals.command_to_accel_mps2(
                command.throttle_ratio, command.brake_ratio, command.deceleration_request_mps2)
        else:
            self.accel_requests[vehicle_id] = MANUAL_ACCEL_MPS2
        # Without lateral automation the driver steers, and the follow world's road is straight.
        self.steering_requests[vehicle_id] = command.steering_angle_request_rad if command.lateral_active \
            else MANUAL_STEERING_RAD

    # ----- time triggers --------------------------------------------------------------------
    def on_step(self, now_s: float) -> None:
        config: SimConfig = self.config
        if now_s > 0:
            self.world.step(now_s - config.step_s, config.step_s, self.accel_requests, self.steering_requests)
        for vehicle_id in self.stack_vehicles:
            body = self.world.bodies[vehicle_id]
            ahead = self.world.vehicle_ahead(vehicle_id)
            self.judge.observe(now_s, vehicle_id, self.world.gap_m(vehicle_id), body.speed_mps,
                               ahead.speed_mps if ahead else None, body.accel_mps2)
        if now_s >= config.duration_s - 1e-9 and not self.finished:
            self.finish(now_s)

    def publish_can_state(self, now_s: float) -> None:
        noise = self.config.world.can
        for vehicle_id in self.stack_vehicles:
            body = self.world.bodies[vehicle_id]
            half_track = body.spec.track_width_m / 2
            wheel = lambda offset: body.speed_mps + offset + self.rng.normal(0, noise.wheel_speed_sigma_mps)  # noqa: E731
            state = vehicle_pb2.VehicleCanState(
                wheel_speed_front_left_mps=wheel(-body.yaw_rate_radps * half_track),
                wheel_speed_front_right_mps=wheel(body.yaw_rate_radps * half_track),
                wheel_speed_rear_left_mps=wheel(-body.yaw_rate_radps * half_track),
                wheel_speed_rear_right_mps=wheel(body.yaw_rate_radps * half_track),
                yaw_rate_radps=body.yaw_rate_radps + self.rng.normal(0, noise.yaw_rate_sigma_radps),
                steering_angle_rad=body.steering_angle_rad, gear=vehicle_pb2.GEAR_DRIVE)
            state.header.sent_time_s = now_s
            self._put_on_bus(vehicle_id, now_s, can_states=[state])

    def publish_gnss(self, now_s: float) -> None:
        world = self.config.world
        for vehicle_id in self.stack_vehicles:
            body = self.world.bodies[vehicle_id]
            east = body.x_m + self.rng.normal(0, world.gnss.sigma_m)
            north = body.y_m + self.rng.normal(0, world.gnss.sigma_m)
            lat, lon, alt = pymap3d.enu2geodetic(east, north, 0.0, world.origin_lat_deg, world.origin_lon_deg,
                                                 world.origin_alt_m)
            fix = gnss_pb2.GnssFix(
                latitude_deg=float(lat), longitude_deg=float(lon), altitude_m=float(alt),
                fix_mode=gnss_pb2.FIX_MODE_RTK_FIXED, std_east_m=world.gnss.sigma_m,
                std_north_m=world.gnss.sigma_m, std_up_m=2 * world.gnss.sigma_m, speed_mps=body.speed_mps,
                course_deg=(90.0 - math.degrees(body.heading_rad)) % 360.0, satellites=14, hdop=0.8)
            self.ctx.publish_for(vehicle_id, "gnss/fix", fix)

    def publish_radar(self, now_s: float) -> None:
        radar = self.config.world.radar
        for vehicle_id in self.stack_vehicles:
            me = self.world.bodies[vehicle_id]
            tracks = sensors_pb2.RadarTracks()
            for other_id, other in self.world.bodies.items():
                if other_id == vehicle_id:
                    continue
                dx, dy = other.rear_bumper_x_m - me.x_m, other.y_m - me.y_m
                forward = dx * math.cos(me.heading_rad) + dy * math.sin(me.heading_rad)
                left = -dx * math.sin(me.heading_rad) + dy * math.cos(me.heading_rad)
                range_m, azimuth = math.hypot(forward, left), math.atan2(left, forward)
                if forward <= 0 or range_m > radar.max_range_m or abs(azimuth) > radar.half_fov_rad:
                    continue
                tracks.tracks.add(track_id=other.spec.station_id % 64,
                                  range_m=range_m + self.rng.normal(0, radar.range_sigma_m), azimuth_rad=azimuth,
                                  range_rate_mps=other.speed_mps - me.speed_mps
                                  + self.rng.normal(0, radar.range_rate_sigma_mps),
                                  width_m=other.spec.width_m)
            tracks.header.sent_time_s = now_s
            self._put_on_bus(vehicle_id, now_s, radar_tracks=[tracks])

    def _put_on_bus(self, vehicle_id: str, now_s: float, **samples) -> None:
        frames = self.vehicle_buses[vehicle_id].frames(now_s, self.config.step_s, **samples)
        if frames is not None:
            self.ctx.publish_for(vehicle_id, "can/vehicle", frames)

    def publish_ground_truth(self, now_s: float) -> None:
        truth = sim_pb2.GroundTruth(collisions=self.judge.collisions)
        for vehicle_id, body in self.world.bodies.items():
            truth.vehicles.add(vehicle_id=vehicle_id, station_id=body.spec.station_id, x_m=body.x_m, y_m=body.y_m,
                               heading_rad=body.heading_rad, speed_mps=body.speed_mps, accel_mps2=body.accel_mps2,
                               yaw_rate_radps=body.yaw_rate_radps, length_m=body.spec.length_m,
                               width_m=body.spec.width_m, station_m=body.x_m, lateral_offset_m=body.y_m,
                               steering_angle_rad=body.steering_angle_rad,
                               automated=vehicle_id in self.stack_vehicles)
        self.ctx.publish_for(WORLD_ID, "ground_truth", truth)

    def finish(self, now_s: float) -> None:
        self.finished = True
        config: SimConfig = self.config
        success, reason = self.judge.verdict()
        result = sim_pb2.RunResult(scenario=config.scenario, seed=config.seed, success=success,
                                   failure_reason=reason, sim_time_s=now_s,
                                   wall_time_s=time.monotonic() - self.wall_start_s)
        for key, value in self.judge.metrics().items():
            result.metrics[key] = value
        result.metrics["participants_lost"] = self.counters.get("participants_lost", 0)
        self.ctx.publish_for(WORLD_ID, "result", result)
        self.ctx.request_stop("scenario finished")
