"""A candump `-l` log (`(t) can0 ID#DATA`) as CanFrames batches on can/vehicle (or can/NAME).

Frames keep the log's own time (timestamp_s; the importer adds the log's --offset to it as to the batch's) and go
out in batches of BATCH_S of it, in log order, each batch at the time of its last frame (when a reader would have
had all of it). Every frame is imported, whatever its id: which ids a car's adapter knows is the replayed service's
business, and it counts the others.
"""

from __future__ import annotations

import io
from pathlib import Path

import can
from can.io.canutils import CanutilsLogReader

from coopdrive.can.wire import to_protobuf
from coopdrive.recording.import_source import SourceReport, TimedMessage
from coopdrive.v1 import vehicle_pb2

DEFAULT_BUS = "vehicle"
BATCH_S = 0.010
MAX_CLASSIC_BYTES = 8
MAX_FD_BYTES = 64


def read_candump_log(path: Path, bus: str = DEFAULT_BUS) -> SourceReport:
    report = SourceReport("candump", path)
    topic = f"can/{bus}"
    batch: list[vehicle_pb2.CanFrame] = []
    batch_start_s = None
    last_s = float("-inf")
    for raw in path.read_bytes().splitlines():
        if not raw.strip():
            continue
        report.items_read += 1
        frame, reason = _parse_line(raw)
        if frame is None:
            report.bad[reason] += 1
            continue
        if frame.timestamp < last_s:
            report.notes["time_went_back"] += 1
        last_s = max(last_s, frame.timestamp)
        if batch and frame.timestamp >= batch_start_s + BATCH_S:
            report.messages.append(_batch_message(topic, batch))
            batch = []
        if not batch:
            batch_start_s = frame.timestamp
        batch.append(to_protobuf(frame))
    if batch:
        report.messages.append(_batch_message(topic, batch))
    return report


def _batch_message(topic: str, frames: list[vehicle_pb2.CanFrame]) -> TimedMessage:
    arrival_s = max(frame.timestamp_s for frame in frames)
    return TimedMessage(arrival_s, topic, vehicle_pb2.CanFrames(frames=frames))


def _parse_line(raw: bytes) -> tuple[can.Message | None, str]:
    """The frame of one log line, or None and why not (python-can reads the format; we check what it lets by)."""
    try:
        text = raw.decode("ascii")
    except UnicodeDecodeError:
        return None, "binary_junk"
    if not text.strip().isprintable():
        return None, "binary_junk"
    fields = text.split()
    if len(fields) not in (3, 4) or not (fields[0].startswith("(") and fields[0].endswith(")")) or "#" not in fields[2]:
        return None, "not_candump"
    identifier, _, data = fields[2].partition("#")
    payload = data[2:] if data.startswith("#") else data
    if not payload.lower().startswith("r") and len(payload) % 2:
        return None, "odd_hex_digits"  # a cut line: python-can would read the last nibble as a byte
    try:
        frame = next(iter(CanutilsLogReader(io.StringIO(text))))
    except (ValueError, IndexError, StopIteration):
        return None, "unparsable"
    if len(identifier) not in (3, 8):
        return None, "bad_id"
    if len(frame.data) > (MAX_FD_BYTES if frame.is_fd else MAX_CLASSIC_BYTES):
        return None, "too_many_bytes"
    return frame, ""
