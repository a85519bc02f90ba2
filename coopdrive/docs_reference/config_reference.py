"""The configuration reference: each service's config keys (its class's `Config`, found through the services
table), the scenario file's keys and the vehicle CAN adapter file's, from their pydantic models."""

from __future__ import annotations

from typing import Sequence

from pydantic import BaseModel

from coopdrive.docs_reference.markdown_table import cell, code, table
from coopdrive.docs_reference.model_reference import model_sections, sections_markdown

CONFIG_INTRO = """# Service configuration

Generated from each service's pydantic config model when the documentation is built: every key a service takes,
its type, its default and what it is. A service reads a YAML or JSON file (`--config FILE`) and then
`--set key.path=value` overrides (repeatable; the value is read as YAML). Nested keys are dotted as `--set` takes
them. An unknown key or a wrong value stops the service before it starts, in one line naming the key:

```sh
coopdrive service planner --set speeed=3
# coopdrive: --set: speeed: Extra inputs are not permitted
```

`coopdrive replay` takes the same `--config` and `--set`, so a setting can be tried on a recorded drive first.
A running service answers `coopdrive/<vehicle>/_info/<service>` with the config it runs with, and recordings keep
it as metadata.
"""

SCENARIO_INTRO = """# Scenario file

Generated from the scenario model (`services/sim/scenario_config.py`) when the documentation is built. A
scenario file is YAML; `coopdrive run my-test.yaml` validates it first and a bad key is one line naming it, before
anything starts. The packaged scenarios (`coopdrive scenarios`) are files of this kind; the
[how-to](../how-to/scenario-file.md) walks through writing one. `faults` items take the keys of their `type`
below; `coopdrive run --fault YAML` adds one to a run.
"""

ADAPTER_INTRO = """# Vehicle CAN adapter file

Generated from `coopdrive.can.adapter.VehicleCanAdapter` when the documentation is built. The file says where a
car's bus carries what the stack reads; geolocation, scene and actuation take it as `vehicle_can`. See the
[how-to](../how-to/vehicle-can.md) for a worked example.
"""


def models_markdown(intro: str, models: Sequence[tuple[str, type[BaseModel]]]) -> str:
    """The intro, then a section of keys per (title, model)."""
    return "\n".join([intro, *(sections_markdown(model_sections(model, title)) for title, model in models)])


def service_config_models() -> list[tuple[str, type[BaseModel]]]:
    """Each service of the services table with its config model."""
    from coopdrive.bus.services import SERVICES
    from coopdrive.runtime.registry import service_class

    return [(f"`{entry.name}`", service_class(entry.name).Config) for entry in SERVICES]


def services_config_markdown() -> str:
    return models_markdown(CONFIG_INTRO, service_config_models())


def packaged_scenarios_markdown() -> str:
    from coopdrive.judging.catalogue import list_scenarios

    rows = [[code(s.name), cell(s.error or s.description), code(s.source)] for s in list_scenarios()]
    return "\n".join(["## Packaged scenarios", "", table(["name", "what happens", "file"], rows), ""])


def scenario_file_markdown() -> str:
    from coopdrive.services.sim.scenario_config import ScenarioConfig

    return "\n".join([models_markdown(SCENARIO_INTRO, []), packaged_scenarios_markdown(),
                      sections_markdown(model_sections(ScenarioConfig, "Keys"))])


def vehicle_can_adapter_markdown() -> str:
    from coopdrive.can.adapter import VehicleCanAdapter

    return models_markdown(ADAPTER_INTRO, [("Keys", VehicleCanAdapter)])
