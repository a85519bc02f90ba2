"""A scenario's SUMO traffic: the vehicles of a SUMO configuration or routes files, driving among ours."""

from __future__ import annotations

from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field, model_validator

from coopdrive.services.sim.sumo_routes import check_routes, route_files_of


class SumoTrafficConfig(BaseModel):
    """Either a SUMO configuration (`config`, a .sumocfg whose route-files SUMO reads) or `routes` (routes and flows
    files), relative to the scenario file's folder; the scenario's map is the network SUMO drives them on."""

    model_config = ConfigDict(extra="forbid")

    config: str | None = None
    routes: list[str] = []
    # SUMO's own step is the simulator's (lockstep); SUMO's collisions are reported, and the vehicles kept.
    collision_action: str = Field(default="warn", pattern="^(warn|none|teleport|remove)$")
    # The share of SUMO's vehicles that are equipped and send CAMs (each drawn once, from the run's seed and its id).
    equipped_share: float = Field(default=0.0, ge=0.0, le=1.0)
    cam_rate_hz: float = Field(default=10.0, gt=0.0)

    @model_validator(mode="after")
    def _one_source(self) -> SumoTrafficConfig:
        if (self.config is None) == (not self.routes):
            raise ValueError("name either a SUMO configuration (config) or routes files (routes), not both or none")
        return self

    def resolved(self, base_dir: Path) -> SumoTrafficConfig:
        """The same traffic with absolute paths, from base_dir."""
        def absolute(name: str) -> str:
            return str((base_dir / Path(name).expanduser()).resolve())
        return self.model_copy(update={"config": absolute(self.config) if self.config else None,
                                       "routes": [absolute(name) for name in self.routes]})

    def routes_files(self) -> list[Path]:
        """The routes files SUMO will read: the configuration's route-files, or those named."""
        if self.config is not None:
            return route_files_of(Path(self.config))
        return [Path(name) for name in self.routes]

    def check(self, network_path: Path) -> None:
        """SumoTrafficError (one line) for a missing file or a route through an edge the network does not have."""
        check_routes(self.routes_files(), network_path)
