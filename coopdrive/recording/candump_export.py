"""A vehicle's CAN bus out of a recording, as a candump log: the simulator's can/vehicle frames (VEH_, RDR_)
and actuation's can/command frames (ACT_), in bus order, for can-utils and python-can's tools."""

from __future__ import annotations

from pathlib import Path

from coopdrive.bus.keys import KeyLayout
from coopdrive.can.candump import CandumpLogger
from coopdrive.can.wire import COMMAND_TOPIC, VEHICLE_BUS_TOPIC, to_python_can
from coopdrive.recording.reader import read_messages, recorded_topics
from coopdrive.v1 import vehicle_pb2

BUS_TOPICS = (VEHICLE_BUS_TOPIC, COMMAND_TOPIC)
CHANNEL = "can0"


class CandumpExportError(ValueError):
    """The recording holds no CAN frames of the vehicle asked for."""


def export_candump(recording: str | Path, vehicle_id: str, out: str | Path) -> int:
    """Writes the vehicle's frames to `out` (a .log file); returns how many."""
    layout = KeyLayout()
    keys = {layout.topic(vehicle_id, topic) for topic in BUS_TOPICS}
    topics = recorded_topics(recording)
    vehicles_with_frames = {layout.split(key)[0] for key in topics if _is_bus_topic(layout, key)}
    frames = []
    for recorded in read_messages(recording, [key for key in topics if key in keys]):
        message = recorded.message
        if isinstance(message, vehicle_pb2.CanFrames):
            frames += message.frames
        elif isinstance(message, vehicle_pb2.CanFrame):
            frames.append(message)
    if not frames:
        found = ", ".join(sorted(vehicles_with_frames)) or "none"
        raise CandumpExportError(
            f"{recording}: no CAN frames of vehicle {vehicle_id!r} (vehicles with frames: {found})")
    with CandumpLogger(out, channel=CHANNEL) as logger:
        # Stable: frames of the same instant keep the order they were put on the bus in.
        for frame in sorted(frames, key=lambda f: f.timestamp_s):
            message = to_python_can(frame)
            message.channel = CHANNEL
            logger.write(message)
    return len(frames)


def _is_bus_topic(layout: KeyLayout, key: str) -> bool:
    parsed = layout.parse(key)
    return parsed is not None and parsed[1] in BUS_TOPICS
