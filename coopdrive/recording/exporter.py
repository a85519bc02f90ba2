"""`coopdrive export`: one topic of a recording as CSV or JSON lines, one row per message (see flatten.py).

Each row starts with `log_time_s` (when the message arrived: the MCAP log time) and `vehicle`, then the
message's fields; this is how a drive gets into pandas (`pandas.read_csv`, `pandas.read_json(lines=True)`).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any, TextIO

from coopdrive.bus.keys import KeyLayout
from coopdrive.recording.flatten import flatten
from coopdrive.recording.reader import read_messages, recorded_topics
from coopdrive.bus.publish_spool import NANOSECONDS

FORMATS = ("csv", "jsonl")


class ExportError(ValueError):
    """Nothing to export: the topic or vehicle is not in the recording."""


def export_rows(recording: str | Path, topic: str, vehicle_id: str | None = None) -> list[dict[str, Any]]:
    """Every message of `topic` (of `vehicle_id` only, when given) as a flat row. `topic` may also be written
    VEHICLE/TOPIC, as the list of recorded topics in the error names them, where no topic has that whole name."""
    layout = KeyLayout()
    # (key, vehicle, topic) of every recorded channel of our key layout.
    channels: list[tuple[str, str, str]] = []
    for key in recorded_topics(recording):
        parsed = layout.parse(key)
        if parsed is not None:
            channels.append((key, *parsed))
    topics_seen = {f"{vehicle}/{name}" for _, vehicle, name in channels}
    if vehicle_id is None and not any(name == topic for _, _, name in channels) and topic in topics_seen:
        vehicle_id, topic = topic.split("/", 1)
    wanted = [key for key, vehicle, name in channels if name == topic and vehicle_id in (None, vehicle)]
    rows = [{"log_time_s": recorded.log_time_ns / NANOSECONDS, "vehicle": layout.split(recorded.topic)[0],
             **flatten(recorded.message)} for recorded in read_messages(recording, wanted)] if wanted else []
    if not rows:
        which = f"vehicle {vehicle_id!r}, topic {topic!r}" if vehicle_id else f"topic {topic!r}"
        raise ExportError(f"{recording}: no messages of {which}; recorded: {', '.join(sorted(topics_seen)) or 'none'}")
    return rows


def write_rows(rows: list[dict[str, Any]], stream: TextIO, file_format: str) -> None:
    if file_format == "jsonl":
        for row in rows:
            stream.write(json.dumps(row) + "\n")
        return
    columns = list(dict.fromkeys(key for row in rows for key in row))  # map keys may differ between rows
    writer = csv.DictWriter(stream, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
