"""The simulator service: owns simulated time, moves the world of a scenario file, feeds every stack its sensors."""

from __future__ import annotations

import time
from importlib import resources
from typing import Literal

from pydantic import Field

from coopdrive.bus.keys import WORLD_ID
from coopdrive.runtime.master import ClockMaster, ClockSettings
from coopdrive.runtime.service import Service, ServiceConfig
from coopdrive.services.sim.scenario_config import SCENARIO_PACKAGE, load_scenario
from coopdrive.services.sim.scenario_feed import ScenarioFeed
from coopdrive.services.sim.service_crashes import crash_outages
from coopdrive.v1 import sim_pb2

# Stacks engage at their starting speed; the margin covers the wheel-speed noise.
FLYING_START_MARGIN_MPS = 1.0


def packaged_scenario_file(name: str) -> str:
    """The path of a scenario packaged with coopdrive (scenarios/NAME.yaml)."""
    return str(resources.files(SCENARIO_PACKAGE) / f"{name}.yaml")


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
    # A scenario file (scenarios/*.yaml or a user's own); "": the packaged scenario named by `scenario`.
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
        """What this world needs in every stack's service configs; the launcher merges its own over them."""
        return scenario_stack_overrides(self.scenario_path())

    def scenario_path(self) -> str:
        return self.scenario_file or packaged_scenario_file(self.scenario)


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
        self.feed = ScenarioFeed(self, config.scenario_path(), config.stacks, config.radio_links,
                                 already_delayed_steps=config.feedback_delay_steps - 1, gnss_ports=config.gnss_ports)

    def stop(self) -> None:
        if getattr(self, "feed", None) is not None:
            self.feed.close()

    # ----- ClockMaster.Driven ---------------------------------------------------------------
    def clock_settings(self) -> ClockSettings:
        c: SimConfig = self.config
        return ClockSettings(step_s=c.step_s, lockstep=c.lockstep, paced=c.paced, realtime_factor=c.realtime_factor,
                             participants=list(c.participants), startup_timeout_s=c.startup_timeout_s,
                             feedback_delay_steps=1 + self._pipelined_steps() if c.lockstep else 1,
                             outages=crash_outages(self.feed.config.faults, c.participants, c.step_s))

    def on_outage(self, participant: str, restart: bool) -> None:
        """Tells the launcher, which owns the processes, to kill the service's process or start it again."""
        self.count("service_restarts" if restart else "service_crashes")
        self.ctx.log.info("service_crash: %s %s at %.2f s", "restarting" if restart else "killing", participant,
                          self.ctx.now_s())
        self.ctx.publish_for(WORLD_ID, "service_fault", sim_pb2.ServiceFault(participant=participant, restart=restart))

    def _pipelined_steps(self) -> int:
        return self.feed.sim.pipelined_steps

    def on_clock_started(self, wall_start_monotonic_s: float) -> None:
        self.wall_start_s = wall_start_monotonic_s

    def on_clock_failed(self, reason: str) -> None:
        """The launcher waits for a result: it gets one that says why the run never started."""
        config: SimConfig = self.config
        self.ctx.publish_for(WORLD_ID, "result", sim_pb2.RunResult(
            scenario=config.scenario, seed=config.seed, success=False, failure_reason=f"the run never started: {reason}"))
