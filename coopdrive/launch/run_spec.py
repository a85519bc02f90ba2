"""RunSpec: what one run is, from the command line to run_scenario, a sweep's task and a remote Dask worker.

Validated once where it is made (its enums refuse a bad value with the field's name); it pickles, so a sweep sends
it to its workers unchanged. What only watches a run (a recording, a gateway, Foxglove, pacing) is RunOptions'
(run.py), beside it.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from coopdrive.launch.process_layout import ProcessLayout
from coopdrive.services.control.longitudinal.types import CaccLaw
from coopdrive.services.sim.world_profile import WorldProfile
from coopdrive.v2x.security.profile import SecurityMode


def merged(base: dict, override: dict) -> dict:
    """base with override on it, section by section."""
    result = dict(base)
    for key, value in override.items():
        result[key] = merged(result[key], value) if isinstance(value, dict) and isinstance(result.get(key), dict) else value
    return result


class RunSpec(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    scenario: str = "follow"
    seed: int = Field(1, ge=0)
    # Simulated seconds (None: the scenario's).
    duration_s: float | None = Field(None, gt=0)
    # Scenario files: how many of the file's stack vehicles run a stack (None: all of them); the others are scripted.
    stacks: int | None = Field(None, ge=1)
    # How the services are spread over processes (`--processes`).
    processes: ProcessLayout = ProcessLayout.VEHICLE
    # The world the scenario runs in: its file's (real unless it says otherwise) or the ideal one.
    world: WorldProfile = WorldProfile.REAL
    # V2X security of every stack (None: the v2x default, off), and the stack vehicles holding a ticket from a root
    # nobody else trusts.
    security: SecurityMode | None = None
    untrusted: tuple[str, ...] = ()
    # Every stack's cooperative law (None: each stack's control config, ours).
    cacc_law: CaccLaw | None = None
    # Faults added to the scenario file's own (fault_config models as dicts, e.g. every V2V link lossy).
    extra_faults: tuple[dict[str, Any], ...] = ()
    # Extra config per service name, merged over the defaults (e.g. {"control": {...}}).
    service_overrides: dict[str, dict[str, Any]] = Field(default_factory=dict)

    def overrides_of(self, service: str) -> dict[str, Any]:
        """What this run sets in a service's config over the defaults: its overrides, the CACC law for control."""
        overrides = self.service_overrides.get(service, {})
        if service == "control" and self.cacc_law is not None:
            overrides = merged(overrides, {"cacc_law": self.cacc_law.value})
        return overrides
