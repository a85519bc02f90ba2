"""Finds the scenario a run names: a packaged YAML file, or a user's own file."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Sequence

import yaml

from coopdrive.roadmap import RoadMap
from coopdrive.services.sim.scenario_builder import check_roads
from coopdrive.services.sim.scenario_config import (SCENARIO_PACKAGE, ScenarioConfig, ScenarioError, VehicleRole,
                                                    load_scenario)


@dataclass(frozen=True)
class ScenarioSource:
    name: str
    file: Path
    config: ScenarioConfig

    def stack_vehicles(self, stacks: int | None) -> list[str]:
        """The vehicle ids that run a coopdrive stack: the file's stack vehicles, the first `stacks` of them."""
        ids = [v.vehicle_id for v in self.config.vehicles if v.role is VehicleRole.STACK]
        if stacks is not None:
            if not 1 <= stacks <= len(ids):
                raise ScenarioError(f"{self.file}: --stacks {stacks}: the scenario has {len(ids)} stack vehicles")
            ids = ids[:stacks]
        return ids

    def check_roads(self) -> None:
        """ScenarioError naming a vehicle or signal approach on a road or lane the map does not have, before
        anything starts (the simulator would stop on it)."""
        try:
            check_roads(self.config, RoadMap.load(self.config.map))
        except (ValueError, OSError) as error:
            raise ScenarioError(f"{self.file}: {error}") from None

    def with_faults(self, faults: Sequence[dict], folder: Path) -> ScenarioSource:
        """The same scenario with faults added to its own, written to folder: the simulator loads a file."""
        data = yaml.safe_load(self.file.read_text(encoding="utf-8"))
        data["faults"] = list(data.get("faults") or []) + list(faults)
        # The map and SUMO's traffic files as loaded: their paths absolute, since the copy is in another folder.
        data["map"] = self.config.map
        if self.config.sumo_traffic is not None:
            data["sumo_traffic"] = self.config.sumo_traffic.model_dump(mode="json")
        path = Path(folder) / f"{self.name}.yaml"
        path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
        return ScenarioSource(self.name, path.resolve(), load_scenario(path))


def resolve_scenario(name_or_path: str) -> ScenarioSource:
    """Raises ScenarioError (one line) for an unknown name or a file that does not validate."""
    path = Path(name_or_path)
    if path.suffix not in (".yaml", ".yml") or not path.exists():
        packaged = resources.files(SCENARIO_PACKAGE) / f"{name_or_path}.yaml"
        if not packaged.is_file():
            known = sorted(entry.name.rsplit(".", 1)[0] for entry in resources.files(SCENARIO_PACKAGE).iterdir()
                           if entry.name.endswith(".yaml"))
            raise ScenarioError(f"{name_or_path}: no such scenario or file; known: {', '.join(known)}")
        path = Path(str(packaged))
    config = load_scenario(path)
    return ScenarioSource(config.name, path.resolve(), config)
