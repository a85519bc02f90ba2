"""Names, ids and integrity rules of the coopdrive vehicle CAN database (vehicle.dbc).

Code refers to frames by `VehicleFrame` name; ids come from the DBC, never from literals.
"""

import enum
from functools import cache
from importlib import resources

import cantools
from cantools.database.can import Database, Message

from coopdrive.can.saturating_packer import SaturatingPacker
from coopdrive.reasons import ReasonedError

DBC_FILE = "vehicle.dbc"
COUNTER_SIGNAL = "Counter"
CHECKSUM_SIGNAL = "Checksum"
COUNTER_MODULO = 16
BYTE_MASK = 0xFF
BITS_PER_BYTE = 8
# ARS 408 tracks up to 100 objects; GCDC radars (ARS 300) reported about 40, which the DBC range allows.
MAX_RADAR_OBJECTS = 40
RADAR_INTERFACE_VERSION = 1


class VehicleFrame(enum.StrEnum):
    LONGITUDINAL_COMMAND = "ACT_LongitudinalCommand"
    STEERING_COMMAND = "ACT_SteeringCommand"
    BODY_COMMAND = "ACT_BodyCommand"
    WHEEL_SPEEDS = "VEH_WheelSpeeds"
    DYNAMICS = "VEH_Dynamics"
    PEDALS = "VEH_Pedals"
    INERTIAL = "VEH_Inertial"
    RADAR_STATUS = "RDR_ObjectListStatus"
    RADAR_OBJECT = "RDR_Object"


COMMAND_FRAMES = (VehicleFrame.LONGITUDINAL_COMMAND, VehicleFrame.STEERING_COMMAND, VehicleFrame.BODY_COMMAND)
FEEDBACK_FRAMES = (VehicleFrame.DYNAMICS, VehicleFrame.PEDALS, VehicleFrame.WHEEL_SPEEDS)
RADAR_FRAMES = (VehicleFrame.RADAR_STATUS, VehicleFrame.RADAR_OBJECT)
INERTIAL_FRAMES = (VehicleFrame.INERTIAL,)
# The simulator sends the feedback frames in FEEDBACK_FRAMES order; the last one closes a cycle.
FEEDBACK_CYCLE_CLOSING_FRAME = FEEDBACK_FRAMES[-1]


class DecodeFailure(enum.Enum):
    NOT_A_DATA_FRAME = "not a data frame"
    UNKNOWN_ID = "unknown frame id"
    WRONG_LENGTH = "wrong length"
    BAD_CHECKSUM = "bad checksum"
    BAD_COUNTER = "bad rolling counter"
    OUT_OF_RANGE = "signal out of range"
    UNEXPECTED_FRAME = "frame not handled by this decoder"


class CanDecodeError(ReasonedError[DecodeFailure], ValueError):
    """A received frame that cannot be trusted; `reason` says why."""


@cache
def load_database() -> Database:
    text = resources.files(__package__).joinpath(DBC_FILE).read_text(encoding="utf-8")
    return cantools.database.load_string(text, database_format="dbc")


@cache
def message(frame: VehicleFrame) -> Message:
    return load_database().get_message_by_name(frame.value)


def frame_id(frame: VehicleFrame) -> int:
    return message(frame).frame_id


@cache
def _frames_by_id() -> dict[int, VehicleFrame]:
    return {frame_id(frame): frame for frame in VehicleFrame}


def frame_by_id(arbitration_id: int) -> VehicleFrame | None:
    return _frames_by_id().get(arbitration_id)


@cache
def has_integrity_signals(frame: VehicleFrame) -> bool:
    names = {signal.name for signal in message(frame).signals}
    return COUNTER_SIGNAL in names and CHECKSUM_SIGNAL in names


@cache
def packer(frame: VehicleFrame) -> SaturatingPacker:
    """The frame's payload packer for simulated values (saturating at the DBC ranges), made once."""
    return SaturatingPacker(message(frame))


@cache
def checksum_byte_index(frame: VehicleFrame) -> int:
    signal = message(frame).get_signal_by_name(CHECKSUM_SIGNAL)
    if signal.start % BITS_PER_BYTE or signal.length != BITS_PER_BYTE:
        raise ValueError(f"{frame}: the checksum must fill one whole byte")
    return signal.start // BITS_PER_BYTE


def checksum(arbitration_id: int, data: bytes, checksum_index: int) -> int:
    """0xFF minus the byte sum of the id and every data byte but the checksum (see the DBC comment)."""
    total = (arbitration_id & BYTE_MASK) + (arbitration_id >> BITS_PER_BYTE)
    total += sum(data) - data[checksum_index]
    return BYTE_MASK - (total & BYTE_MASK)
