"""The scenarios coopdrive knows: the built-in follow world and the YAML files of coopdrive.scenarios."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

import yaml

from coopdrive.judging.score import JudgingParameters
from coopdrive.services.sim.scenario_config import ScenarioConfig, ScenarioError, parse_scenario

SCENARIO_PACKAGE = "coopdrive.scenarios"
# Scenarios the simulator builds in code (services/sim/service.py), with what `run NAME` does.
BUILT_IN = {"follow": "a scripted leader changes speed; the ego stack follows at d = r + h v (r = 6 m, h = 1.5 s)"}


@dataclass(frozen=True)
class ScenarioEntry:
    name: str
    description: str
    source: str  # "built-in" or the YAML file name
    error: str = ""


def scenario_files() -> dict[str, ScenarioConfig | ScenarioError]:
    """File name -> the parsed scenario, or the one-line error that stops it loading."""
    loaded: dict[str, ScenarioConfig | ScenarioError] = {}
    for entry in sorted(resources.files(SCENARIO_PACKAGE).iterdir(), key=lambda e: e.name):
        if not entry.name.endswith((".yaml", ".yml")):
            continue
        try:
            loaded[entry.name] = parse_scenario(yaml.safe_load(entry.read_text(encoding="utf-8")), entry.name)
        except yaml.YAMLError as error:
            loaded[entry.name] = ScenarioError(f"{entry.name}: invalid YAML: {' '.join(str(error).split())}")
        except ScenarioError as error:
            loaded[entry.name] = error
    return loaded


def list_scenarios() -> list[ScenarioEntry]:
    """Built-in scenarios first (described by their YAML file when one has the same name), then the others."""
    entries = {name: ScenarioEntry(name, description, "built-in") for name, description in BUILT_IN.items()}
    for file_name, scenario in scenario_files().items():
        if isinstance(scenario, ScenarioError):
            stem = file_name.rsplit(".", 1)[0]
            entries.setdefault(stem, ScenarioEntry(stem, "", file_name, str(scenario)))
        elif scenario.name in BUILT_IN:
            entries[scenario.name] = ScenarioEntry(scenario.name, scenario.description or BUILT_IN[scenario.name],
                                                   f"built-in, {file_name}")
        else:
            entries.setdefault(scenario.name, ScenarioEntry(scenario.name, scenario.description, file_name))
    return list(entries.values())


def judging_parameters(name: str) -> JudgingParameters:
    """The judging section of the scenario file called `name`, or the judge's defaults."""
    for scenario in scenario_files().values():
        if isinstance(scenario, ScenarioConfig) and scenario.name == name:
            judging = scenario.judging
            return JudgingParameters(safety_radius_m=judging.safety_radius_m, standstill_m=judging.standstill_m,
                                     headway_s=judging.headway_s, string_start_s=judging.string_start_s,
                                     string_frequency_hz=judging.string_frequency_hz,
                                     string_end_s=judging.string_end_s,
                                     platoon=tuple(judging.platoon))
    return JudgingParameters()
