"""The scenarios coopdrive knows: the YAML files of coopdrive.scenarios."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import yaml

from coopdrive.judging.score import JudgingParameters
from coopdrive.services.sim.scenario_config import (SCENARIO_PACKAGE, ScenarioConfig, ScenarioError, load_scenario,
                                                    parse_scenario)


@dataclass(frozen=True)
class ScenarioEntry:
    name: str
    description: str
    source: str  # the YAML file name
    error: str = ""


def scenario_files() -> dict[str, ScenarioConfig | ScenarioError]:
    """File name -> the parsed scenario, or the one-line error that stops it loading."""
    loaded: dict[str, ScenarioConfig | ScenarioError] = {}
    for entry in sorted(resources.files(SCENARIO_PACKAGE).iterdir(), key=lambda e: e.name):
        if not entry.name.endswith((".yaml", ".yml")):
            continue
        try:
            # A SUMO network a file names is beside it (scenarios/sumo/): found from the file's own folder.
            loaded[entry.name] = parse_scenario(yaml.safe_load(entry.read_text(encoding="utf-8")), entry.name,
                                                Path(str(entry)).parent)
        except yaml.YAMLError as error:
            loaded[entry.name] = ScenarioError(f"{entry.name}: invalid YAML: {' '.join(str(error).split())}")
        except ScenarioError as error:
            loaded[entry.name] = error
    return loaded


def list_scenarios() -> list[ScenarioEntry]:
    """Every packaged scenario file, with the one-line error of a file that does not load."""
    entries: dict[str, ScenarioEntry] = {}
    for file_name, scenario in scenario_files().items():
        if isinstance(scenario, ScenarioError):
            stem = file_name.rsplit(".", 1)[0]
            entries.setdefault(stem, ScenarioEntry(stem, "", file_name, str(scenario)))
        else:
            entries.setdefault(scenario.name, ScenarioEntry(scenario.name, scenario.description, file_name))
    return list(entries.values())


def judging_parameters(name: str) -> JudgingParameters:
    """The judging section of the scenario called `name` (a packaged one, or a scenario file's path), or the
    judge's defaults for a recording of no known scenario."""
    scenario = _scenario_called(name)
    if scenario is None:
        return JudgingParameters()
    judging = scenario.judging
    return JudgingParameters(safety_radius_m=judging.safety_radius_m, standstill_m=judging.standstill_m,
                             headway_s=judging.headway_s, string_start_s=judging.string_start_s,
                             string_frequency_hz=judging.string_frequency_hz, string_end_s=judging.string_end_s,
                             platoon=tuple(judging.platoon))


def _scenario_called(name: str) -> ScenarioConfig | None:
    for scenario in scenario_files().values():
        if isinstance(scenario, ScenarioConfig) and scenario.name == name:
            return scenario
    if name and Path(name).is_file():
        try:
            return load_scenario(Path(name))
        except ScenarioError:
            return None
    return None
