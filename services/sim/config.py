"""The simulator's config, apart from its service: the launcher builds a run from it without importing the
simulator itself (which a run's processes load while they start)."""

from __future__ import annotations

from importlib import resources
from typing import Literal

from pydantic import Field

from coopdrive.runtime.master import ClockConfig
from coopdrive.runtime.service import ServiceConfig
from coopdrive.services.sim.scenario_config import SCENARIO_PACKAGE, load_scenario

# Stacks engage at their starting speed; the margin covers the wheel-speed noise.
FLYING_START_MARGIN_MPS = 1.0


def packaged_scenario_file(name: str) -> str:
    """The path of a scenario packaged with coopdrive (scenarios/NAME.yaml)."""
    return str(resources.files(SCENARIO_PACKAGE) / f"{name}.yaml")


class SimConfig(ServiceConfig, ClockConfig):
    scenario: str = "follow"
    seed: int = 1
    duration_s: float = 60.0
    step_s: float = 0.02
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
