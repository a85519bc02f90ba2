"""VehicleCanAdapter: where a car's bus carries each quantity the stack reads, as a YAML file beside its DBC.

One adapter per car, shared by geolocation (odometry, yaw rate), scene (radar) and actuation (driver feedback);
services take its path through their `vehicle_can` config key. A quantity is the sum of one or more signals of
one message (the RAV4's steering-wheel angle is STEER_ANGLE + STEER_FRACTION), times a unit conversion to SI, a
scale and a sign. The packaged `vehicle_adapter.yaml` describes the simulator's car (`vehicle.dbc`) and is the
default. Counters and checksums are checked only on messages whose DBC has the signals the adapter names for them.
"""

from __future__ import annotations

import enum
import math
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Annotated

import cantools
import yaml
from cantools.database.can import Database, Message
from pydantic import AfterValidator, BaseModel, ConfigDict, Field, ValidationError, model_validator

from coopdrive.v1 import vehicle_pb2

DEFAULT_ADAPTER = "vehicle_adapter.yaml"
KMH_TO_MPS = 1.0 / 3.6

# Unit conversions to SI: the unit a DBC states for the signal (after its own scale and offset).
UNIT_TO_SI = {
    "": 1.0, "m/s": 1.0, "rad": 1.0, "rad/s": 1.0, "m/s^2": 1.0, "ratio": 1.0, "bar": 1.0,
    "km/h": KMH_TO_MPS, "mph": 0.44704, "deg": math.pi / 180.0, "deg/s": math.pi / 180.0,
    "g": 9.80665, "percent": 0.01, "kPa": 0.01,
}


class ChecksumKind(enum.Enum):
    NONE = "none"
    # vehicle.dbc: 0xFF minus the byte sum of the id and the other data bytes.
    COOPDRIVE = "coopdrive"
    # Toyota: the byte sum of the id bytes, the frame length and every data byte but the last (the checksum).
    TOYOTA = "toyota"


class VehicleCanAdapterError(ValueError):
    """An adapter file that cannot be used; the message names the file and what is wrong."""


class Quantity(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    message: str = Field(min_length=1)
    # Summed after the DBC's own scaling.
    signals: tuple[str, ...] = Field(min_length=1)
    unit: str = ""
    scale: float = 1.0
    sign: float = Field(1.0, description="+1 or -1: flips the car's convention to ours")
    # For flags (turn signals, brake switch): true when the summed raw value is one of these.
    equals: tuple[float, ...] | None = None

    @model_validator(mode="after")
    def _known_unit_and_sign(self) -> Quantity:
        if self.unit not in UNIT_TO_SI:
            raise ValueError(f"unit {self.unit!r} is not one of {sorted(UNIT_TO_SI)}")
        if self.sign not in (1.0, -1.0):
            raise ValueError(f"sign must be 1 or -1, not {self.sign}")
        return self

    def value(self, decoded: dict[str, float]) -> float:
        total = sum(float(decoded[name]) for name in self.signals)
        if self.equals is not None:
            return 1.0 if total in self.equals else 0.0
        return self.sign * self.scale * UNIT_TO_SI[self.unit] * total


class GearSource(BaseModel):
    """The gear lever: which raw values of one signal mean park, reverse, neutral and drive."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    message: str = Field(min_length=1)
    signal: str = Field(min_length=1)
    park: tuple[int, ...] = ()
    reverse: tuple[int, ...] = ()
    neutral: tuple[int, ...] = ()
    drive: tuple[int, ...] = ()

    def gear(self, raw: float) -> int:
        for values, gear in ((self.park, vehicle_pb2.GEAR_PARK), (self.reverse, vehicle_pb2.GEAR_REVERSE),
                             (self.neutral, vehicle_pb2.GEAR_NEUTRAL), (self.drive, vehicle_pb2.GEAR_DRIVE)):
            if int(raw) in values:
                return gear
        return vehicle_pb2.GEAR_UNSPECIFIED


class Integrity(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    checksum: ChecksumKind = ChecksumKind.NONE
    checksum_signal: str = "CHECKSUM"
    # "" = no rolling counter is checked.
    counter_signal: str = ""


class OdometryOptions(BaseModel):
    """How geolocation turns this car's wheel speeds into speed and yaw rate."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    # rear: the rear-axle wheels (the ego state's reference point; no traction slip on a front-driven car);
    # all: the mean of the four, when the tyres' radii differ more than the rear pair tells.
    speed_wheels: str = Field("rear", pattern="^(rear|all)$")
    # False when the car's yaw-rate sensor is to be trusted over the difference of the rear wheels (tyres of
    # unequal radius make that difference a bias of degrees per second).
    yaw_rate_from_wheels: bool = True
    # Estimate the wheel-radius scale against GNSS speed (the simulator's car knows its wheel radius exactly).
    estimate_wheel_scale: bool = False
    # One wheel's speed noise (one sigma); None: geolocation's geolocator.wheel_speed_std_mps.
    wheel_speed_std_mps: float | None = Field(None, gt=0.0)


class MountPoint(BaseModel):
    """A point of the car in the vehicle frame: metres ahead of (x) and left of (y) the middle of the rear axle,
    the reference point of the ego state geolocation publishes."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    x_m: float
    y_m: float = 0.0


class Mounting(BaseModel):
    """Where the car's sensors sit (None: not given; the service's own default or config key applies)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    # The GNSS antenna's phase centre: geolocation's lever arm (its geolocator.antenna_x_m / antenna_y_m, when
    # set, win over this).
    gnss_antenna: MountPoint | None = None


# The quantities a VehicleCanState carries (vehicle.proto), by adapter name.
STATE_QUANTITIES = (
    "wheel_speed_front_left", "wheel_speed_front_right", "wheel_speed_rear_left", "wheel_speed_rear_right",
    "vehicle_speed", "steering_wheel_angle", "accelerator_pedal", "brake_pedal", "brake_pressure",
    "turn_signal_left", "turn_signal_right",
)
# The car's inertial sensor: an ImuSample each time the yaw rate's message arrives.
INERTIAL_QUANTITIES = ("yaw_rate", "accel_longitudinal", "accel_lateral")
WHEEL_SPEEDS = STATE_QUANTITIES[:4]


class VehicleCanAdapter(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    # Relative to the adapter file.
    dbc: str = Field(min_length=1)
    # Steering-wheel angle over road-wheel angle (1 when the bus carries the road-wheel angle itself).
    steering_ratio: float = Field(gt=0.0)
    quantities: dict[str, Quantity]
    gear: GearSource | None = None
    integrity: Integrity = Integrity()
    odometry: OdometryOptions = OdometryOptions()
    mounting: Mounting = Mounting()
    # The VehicleCanState goes out when this message arrives (default: the wheel speeds'), once it and these
    # messages have been seen; a quantity of a message not seen yet reads 0 (a blinker frame may come once in
    # seconds: the odometry need not wait for it).
    state_message: str = ""
    state_requires: tuple[str, ...] = ()
    # Refuse a frame whose used signals fall outside their DBC range. Off for DBCs whose ranges are not physical
    # (opendbc often writes the raw range, e.g. [0|65535] for a yaw rate with an offset of -125 deg/s).
    check_ranges: bool = True
    # The car has a radar sending coopdrive's object list (RDR_ frames of vehicle.dbc), which scene decodes from
    # the frames it reads (can/vehicle, or the radar's own bus when scene's can_port names one).
    radar_object_list: bool = False
    # Where this adapter came from (set by load_adapter).
    source: str = ""

    @model_validator(mode="after")
    def _known_quantities(self) -> VehicleCanAdapter:
        unknown = set(self.quantities) - set(STATE_QUANTITIES) - set(INERTIAL_QUANTITIES)
        if unknown:
            raise ValueError(f"unknown quantities {sorted(unknown)}; known: "
                             f"{', '.join(STATE_QUANTITIES + INERTIAL_QUANTITIES)}")
        missing = [name for name in WHEEL_SPEEDS if name not in self.quantities]
        if missing:
            raise ValueError(f"the wheel speeds are needed: {', '.join(missing)} missing")
        return self

    @property
    def closing_message(self) -> str:
        return self.state_message or self.quantities["wheel_speed_rear_left"].message

    @property
    def has_yaw_rate_sensor(self) -> bool:
        return "yaw_rate" in self.quantities


def load_adapter(path: str | Path | None = None) -> tuple[VehicleCanAdapter, Database]:
    """The adapter at `path` (None: the simulator's car) and its DBC, checked against each other.

    Raises VehicleCanAdapterError with one line naming the file and the problem.
    """
    return _load(None if path is None else str(Path(path).resolve()))


@cache
def _load(path: str | None) -> tuple[VehicleCanAdapter, Database]:
    if path is None:
        folder = resources.files(__package__)
        text, name = folder.joinpath(DEFAULT_ADAPTER).read_text(encoding="utf-8"), DEFAULT_ADAPTER
    else:
        try:
            text, name = Path(path).read_text(encoding="utf-8"), path
        except OSError as error:
            raise VehicleCanAdapterError(f"vehicle_can: cannot read {path}: {error.strerror}") from error
    try:
        adapter = VehicleCanAdapter.model_validate({**(yaml.safe_load(text) or {}), "source": name})
    except (yaml.YAMLError, ValidationError, TypeError) as error:
        raise VehicleCanAdapterError(f"vehicle_can {name}: {_one_line(error)}") from error
    dbc_text = (folder.joinpath(adapter.dbc).read_text(encoding="utf-8") if path is None
                else _read_dbc(Path(path).parent / adapter.dbc, name))
    try:
        database = cantools.database.load_string(dbc_text, database_format="dbc")
    except Exception as error:  # cantools raises its own parse errors and plain ValueErrors
        raise VehicleCanAdapterError(f"vehicle_can {name}: DBC {adapter.dbc} does not load: {error}") from error
    _check_names(adapter, database, name)
    return adapter, database


def _read_dbc(path: Path, adapter_name: str) -> str:
    try:
        # DBC files from the wild are often Latin-1 (degree signs in comments).
        return path.read_text(encoding="latin-1")
    except OSError as error:
        raise VehicleCanAdapterError(f"vehicle_can {adapter_name}: cannot read DBC {path}: {error.strerror}") from error


def _check_names(adapter: VehicleCanAdapter, database: Database, name: str) -> None:
    wanted = [(q.message, s) for q in adapter.quantities.values() for s in q.signals]
    if adapter.gear is not None:
        wanted.append((adapter.gear.message, adapter.gear.signal))
    others = [(adapter.closing_message, None)] + [(m, None) for m in adapter.state_requires]
    for message_name, signal_name in wanted + others:
        message = _message(database, message_name, name)
        if signal_name is not None and signal_name not in {s.name for s in message.signals}:
            raise VehicleCanAdapterError(f"vehicle_can {name}: message {message_name} has no signal {signal_name}")


def _message(database: Database, message_name: str, adapter_name: str) -> Message:
    try:
        return database.get_message_by_name(message_name)
    except KeyError:
        raise VehicleCanAdapterError(f"vehicle_can {adapter_name}: the DBC has no message {message_name}") from None


def _one_line(error: Exception) -> str:
    if isinstance(error, ValidationError):
        first = error.errors()[0]
        where = ".".join(str(part) for part in first["loc"])
        return f"{where}: {first['msg']}" if where else first["msg"]
    return " ".join(str(error).split())


def _usable_adapter(path: str | None) -> str | None:
    if path is not None:
        load_adapter(path)  # VehicleCanAdapterError is a ValueError: the config is refused with its one line
    return path


# The services' `vehicle_can` key: the car's adapter file (None: the simulator's car), checked when loaded.
VehicleCanPath = Annotated[str | None, AfterValidator(_usable_adapter)]
