"""`coopdrive export RECORDING --foxglove OUT.mcap`: an older recording (made before recordings carried them)
again with the channels Foxglove draws, derived as a recording made now would have them."""

from __future__ import annotations

from pathlib import Path

from coopdrive.recording.reader import read_messages, read_metadata
from coopdrive.recording.writer import McapRecorder


def export_foxglove(recording: str | Path, out: str | Path) -> int:
    """Copies every stack message and the metadata, adding the visual channels; returns the messages copied.
    Visual channels the recording already holds are derived anew, not copied twice."""
    recorder = McapRecorder(out, read_metadata(recording))
    try:
        for recorded in read_messages(recording):
            recorder.write(recorded.topic, recorded.message, log_time_ns=recorded.log_time_ns)
    finally:
        recorder.close()
    return recorder.messages_written
