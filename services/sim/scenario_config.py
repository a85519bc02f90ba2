"""Scenario files: pydantic models and a loader whose error is one line naming the bad key path."""
from __future__ import annotations

import datetime as dt
import enum
import math
import re
from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, model_validator

from coopdrive.roadmap.sumo_network import SumoNetworkError, check_sumo_network, names_sumo_network
from coopdrive.roadmap.sumo_placement import SumoPlacementError, station_on_sumo_lane
from coopdrive.services.sim.channel_config import RadioChannelConfig
from coopdrive.services.sim.fault_config import Fault
from coopdrive.services.sim.intersection_config import SignalisedIntersection
from coopdrive.services.sim.profiles import PLANT_PERTURBATIONS, PlantPerturbation, VehicleProfile, plant_profile
from coopdrive.services.sim.roadside_unit import RsuEvent
from coopdrive.services.sim.sensor_config import SensorSuiteConfig
from coopdrive.services.sim.speed_profiles import LaneChange, SpeedProfile
from coopdrive.services.sim.sumo_routes import SumoTrafficError
from coopdrive.services.sim.sumo_traffic_config import SumoTrafficConfig
from coopdrive.services.sim.world_profile import WorldProfile, ideal
from coopdrive.vehicle import VehicleKind, vehicle_of

GCDC_2016_FINAL = dt.datetime(2016, 5, 28, 10, 0, 0, tzinfo=dt.timezone.utc)
# Keys that select a member of a tagged union; pydantic puts their value in error paths.
_TAG_KEYS = ("type", "kind")
# A validator's message that starts with the key path it is about ("station_m: ...", "vehicles.2.edge: ...").
_OWN_KEY = re.compile(r"^[a-z_][a-z0-9_]*(\.[a-z0-9_]+)*: ")


# The validation context's key for the folder a scenario file's relative paths are from.
BASE_DIR_CONTEXT = "base_dir"
# The package that holds the scenario files coopdrive ships (scenarios/*.yaml).
SCENARIO_PACKAGE = "coopdrive.scenarios"


class ScenarioError(ValueError):
    """A scenario that cannot be used; str() is one line: '<source>: <key.path>: <message>'."""


class VehicleRole(enum.Enum):
    STACK = "stack"          # runs the coopdrive stack (automated, judged)
    SCRIPTED = "scripted"    # a behaviour object (participants.ScriptedVehicle)
    EMERGENCY = "emergency"  # participants.EmergencyVehicle


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class SirenConfig(_Strict):
    on_s: float = Field(default=0.0, ge=0)
    off_s: float = math.inf


class VehicleConfig(_Strict):
    vehicle_id: str = Field(min_length=1)
    station_id: int = Field(ge=0, lt=2 ** 32)
    role: VehicleRole = VehicleRole.STACK
    profile: VehicleKind = VehicleKind.PASSENGER_CAR
    # Where the simulated vehicle differs from its description on purpose (None: the kind's documented
    # perturbation, profiles.PLANT_PERTURBATIONS): a controller tested against its own model exactly proves little.
    plant: PlantPerturbation | None = None
    # Road id in the map; empty means the map's first road.
    road: str = ""
    lane: int = Field(ge=0)
    # Metres along the lane; on a SUMO network, `edge` and `pos_m` may place the vehicle instead (as SUMO places one:
    # pos_m from the start of the edge's lane, by SUMO's length), and the scenario's loading sets station_m.
    station_m: float | None = None
    edge: str | None = Field(default=None, min_length=1)
    pos_m: float | None = None
    speed_mps: float = Field(ge=0)
    speed_profile: SpeedProfile | None = None
    lane_changes: list[LaneChange] = []
    lateral_offset_m: float = 0.0
    ignores_protocol: bool = False
    # The organiser's vehicle at the intersection: every stack is told its station id and gives way to it.
    organiser: bool = False
    # GCDC platoon id (1 = A, 2 = B); None outside platoons.
    platoon: int | None = Field(default=None, ge=1)
    siren: SirenConfig | None = None
    # Overrides the scenario-wide sensor suite for this vehicle.
    sensors: SensorSuiteConfig | None = None

    @model_validator(mode="after")
    def _placed_once(self) -> VehicleConfig:
        """Either road and station_m, or edge and pos_m (road is then the edge)."""
        if self.edge is None:
            if self.pos_m is not None:
                raise ValueError("pos_m: a position on a SUMO edge needs the edge (edge: ID)")
            if self.station_m is None:
                raise ValueError("station_m: Field required")
            return self
        if self.road not in ("", self.edge):
            raise ValueError(f"edge: give either road or edge, not both (road {self.road!r}, edge {self.edge!r})")
        if self.pos_m is None:
            raise ValueError("pos_m: a vehicle placed on a SUMO edge needs its position on it (pos_m)")
        if self.station_m is not None:
            raise ValueError("station_m: give either station_m or pos_m on the edge, not both")
        self.road = self.edge
        return self

    def plant_profile(self) -> VehicleProfile:
        """The simulated vehicle: its description with its plant's perturbation."""
        return plant_profile(vehicle_of(self.profile), self.plant or PLANT_PERTURBATIONS[self.profile])


class RoadsideUnitConfig(_Strict):
    unit_id: str = Field(min_length=1)
    station_id: int = Field(ge=0, lt=2 ** 32)
    x_m: float
    y_m: float
    rate_hz: float = Field(default=25.0, gt=0)
    events: list[RsuEvent] = []
    # The signalised intersection whose MAPEM and SPATEM the unit sends, with its signal controller.
    intersection: SignalisedIntersection | None = None


class JudgingConfig(_Strict):
    # Vehicle ids leader first, for the string gain.
    platoon: list[str] = []
    safety_radius_m: float = Field(default=7.5, gt=0)
    standstill_m: float = Field(default=6.0, ge=0)
    headway_s: float = Field(default=1.5, ge=0)
    string_start_s: float = Field(default=0.0, ge=0)
    # The leader's excitation. Only a run that declares one is judged on its string gain: behind a steady leader
    # the gain is reported, but it is a ratio of noise amplitudes.
    string_frequency_hz: float | None = Field(default=None, gt=0)
    # The string gain is measured up to here (before a final brake that is no longer the excitation).
    string_end_s: float = Field(default=math.inf, gt=0)


class Mission(enum.Enum):
    """What the stacks' planners do in the scenario (coopdrive.v1.Scenario)."""

    FOLLOW = "follow"
    PLATOON = "platoon"
    MERGE = "merge"
    INTERSECTION = "intersection"
    EMERGENCY = "emergency"


class EngageMode(enum.Enum):
    """The driving mode every stack engages at the start, as its safety driver would."""

    AUTONOMOUS = "autonomous"    # longitudinal and lateral
    COOPERATIVE = "cooperative"  # longitudinal; the simulator's lane-keeping driver steers


class ScenarioConfig(_Strict):
    name: str = Field(min_length=1)
    description: str = ""
    mission: Mission = Mission.FOLLOW
    # A shipped map's name, a GeoJSON file, or a SUMO network (.net.xml; a relative path is from the scenario file's
    # folder, and the loaded scenario holds it absolute, for every process of the run).
    map: str = "a270"
    seed: int = Field(default=0, ge=0)
    duration_s: float = Field(gt=0)
    step_s: float = Field(default=0.02, gt=0)
    utc_epoch: dt.datetime = GCDC_2016_FINAL
    vehicles: list[VehicleConfig] = Field(min_length=1)
    roadside_units: list[RoadsideUnitConfig] = []
    sensors: SensorSuiteConfig = SensorSuiteConfig()
    channel: RadioChannelConfig = RadioChannelConfig()
    faults: list[Fault] = []
    engage: EngageMode = EngageMode.AUTONOMOUS
    judging: JudgingConfig = JudgingConfig()
    # The real world (every sensor's and the radio's error sources, driving resistance, scripted vehicles'
    # CAMs from their own GNSS) or the ideal one for tests needing exact answers (world_profile.py).
    world: WorldProfile = WorldProfile.REAL
    # SUMO's vehicles driving among ours on the scenario's SUMO network (docs/how-to/sumo-network.md).
    sumo_traffic: SumoTrafficConfig | None = None

    @model_validator(mode="after")
    def _world_applied(self) -> ScenarioConfig:
        if self.world is WorldProfile.IDEAL:
            self.sensors = ideal(self.sensors)
            self.channel = ideal(self.channel)
            for vehicle in self.vehicles:
                if vehicle.sensors is not None:
                    vehicle.sensors = ideal(vehicle.sensors)
        return self

    @model_validator(mode="after")
    def _sumo_network_read(self, info: ValidationInfo) -> ScenarioConfig:
        """A SUMO network is read here, so that a missing or unusable one stops the run before anything starts."""
        if names_sumo_network(self.map):
            base_dir = Path((info.context or {}).get(BASE_DIR_CONTEXT, "."))
            path = (base_dir / Path(self.map).expanduser()).resolve()
            try:
                check_sumo_network(path)
            except SumoNetworkError as error:
                raise ValueError(f"map: {error}") from None
            self.map = str(path)
        return self

    @model_validator(mode="after")
    def _sumo_traffic_read(self, info: ValidationInfo) -> ScenarioConfig:
        """SUMO traffic's files are checked here against the network, so that nothing starts on a bad one."""
        if self.sumo_traffic is None:
            return self
        if not names_sumo_network(self.map):
            raise ValueError(f"sumo_traffic: SUMO traffic needs a SUMO network as the map, not {self.map!r}")
        traffic = self.sumo_traffic.resolved(Path((info.context or {}).get(BASE_DIR_CONTEXT, ".")))
        try:
            traffic.check(Path(self.map))
        except SumoTrafficError as error:
            raise ValueError(f"sumo_traffic: {error}") from None
        self.sumo_traffic = traffic
        return self

    @model_validator(mode="after")
    def _sumo_positions_placed(self) -> ScenarioConfig:
        """Vehicles placed by SUMO edge and position get their station on our lane here, and one that is not on the
        network stops the run before anything starts."""
        for index, vehicle in enumerate(self.vehicles):
            if vehicle.edge is None:
                continue
            if not names_sumo_network(self.map):
                raise ValueError(f"vehicles.{index}.edge: placing by SUMO edge needs a SUMO network as the map, "
                                 f"not {self.map!r}")
            try:
                vehicle.station_m = station_on_sumo_lane(self.map, vehicle.edge, vehicle.lane, vehicle.pos_m)
            except SumoPlacementError as error:
                raise ValueError(f"vehicles.{index}: {error}") from None
        return self

    @model_validator(mode="after")
    def _references_resolve(self) -> ScenarioConfig:
        ids = [v.vehicle_id for v in self.vehicles]
        for index, vehicle_id in enumerate(ids):
            if vehicle_id in ids[:index]:
                raise ValueError(f"vehicles.{index}.vehicle_id: duplicate vehicle_id {vehicle_id!r}")
        stations = [v.station_id for v in self.vehicles] + [u.station_id for u in self.roadside_units]
        if len(set(stations)) != len(stations):
            raise ValueError("station_id: every vehicle and roadside unit needs its own station_id")
        signalised = [u.unit_id for u in self.roadside_units if u.intersection is not None]
        for index, fault in enumerate(self.faults):
            vehicle_id = getattr(fault, "vehicle_id", None)
            if vehicle_id is not None and vehicle_id not in ids:
                raise ValueError(f"faults.{index}.vehicle_id: unknown vehicle {vehicle_id!r}")
            unit_id = getattr(fault, "unit_id", None)
            if unit_id is not None and unit_id not in signalised:
                raise ValueError(f"faults.{index}.unit_id: no roadside unit {unit_id!r} with an intersection")
        for index, vehicle_id in enumerate(self.judging.platoon):
            if vehicle_id not in ids:
                raise ValueError(f"judging.platoon.{index}: unknown vehicle {vehicle_id!r}")
        return self

    def sensors_of(self, vehicle: VehicleConfig) -> SensorSuiteConfig:
        return vehicle.sensors or self.sensors

    def in_world(self, world: WorldProfile) -> ScenarioConfig:
        """This scenario in the given world: the ideal one applies to whatever the file did not set itself;
        asking for the real one keeps the file's own choice."""
        if world is WorldProfile.REAL or self.world is WorldProfile.IDEAL:
            return self
        return self.model_validate({**dict(self), "world": world})


def _key_path(loc: tuple[Any, ...], data: Any) -> str:
    """Dotted path of a pydantic error location, without the tags pydantic adds for tagged unions."""
    parts: list[str] = []
    node = data
    for element in loc:
        if isinstance(node, dict) and element not in node and any(node.get(k) == element for k in _TAG_KEYS):
            continue
        parts.append(str(element))
        if isinstance(node, dict):
            node = node.get(element)
        elif isinstance(node, list) and isinstance(element, int) and element < len(node):
            node = node[element]
        else:
            node = None
    return ".".join(parts)


def _one_line(text: str) -> str:
    return " ".join(text.split())


def parse_scenario(data: Any, source: str = "<scenario>", base_dir: Path | None = None) -> ScenarioConfig:
    """base_dir: the folder the file's relative paths (a SUMO network) are from; else the working directory."""
    try:
        return ScenarioConfig.model_validate(data, context={BASE_DIR_CONTEXT: str(base_dir or ".")})
    except ValidationError as error:
        first = error.errors()[0]
        path = _key_path(tuple(first["loc"]), data)
        message = first["msg"]
        own_key = _OWN_KEY.match(message.removeprefix("Value error, ")) or (not path and ": " in message)
        if message.startswith("Value error, ") and own_key:
            # Cross-reference errors carry their own key path, below where they were raised.
            own, message = message.removeprefix("Value error, ").split(": ", 1)
            path = f"{path}.{own}" if path else own
        more = error.error_count() - 1
        suffix = f" (and {more} more error{'s' if more > 1 else ''})" if more else ""
        raise ScenarioError(_one_line(f"{source}: {path or '<root>'}: {message}{suffix}")) from None


def load_scenario(path: str | Path) -> ScenarioConfig:
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise ScenarioError(_one_line(f"{path}: cannot read: {error.strerror or error}")) from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f"line {mark.line + 1}" if mark is not None else "?"
        raise ScenarioError(_one_line(f"{path}: invalid YAML at {where}: {getattr(error, 'problem', error)}")) from None
    return parse_scenario(data, str(path), path.parent)
