"""GatewayRecording: POST /recording writes what the gateway hears to an MCAP file.

start/stop run on the worker thread (handed over with call_soon), like write, which the bus
handlers call; status may be read from any thread.
"""

from __future__ import annotations

import threading
from pathlib import Path

from google.protobuf.message import Message

from coopdrive.bus.keys import KeyLayout
from coopdrive.recording.writer import LIVE_CHUNK_BYTES, McapRecorder


class GatewayRecording:
    def __init__(self, directory: Path | None):
        self.directory = directory
        self._layout = KeyLayout()
        self._lock = threading.Lock()
        self._recorder: McapRecorder | None = None

    @property
    def path(self) -> Path | None:
        with self._lock:
            return self._recorder.path if self._recorder is not None else None

    def start(self, path: Path) -> None:
        recorder = McapRecorder(path, chunk_bytes=LIVE_CHUNK_BYTES)
        with self._lock:
            previous, self._recorder = self._recorder, recorder
        if previous is not None:
            previous.close()

    def stop(self) -> int:
        """Closes the file; returns the messages written, 0 if not recording."""
        with self._lock:
            recorder, self._recorder = self._recorder, None
        if recorder is None:
            return 0
        recorder.close()
        return recorder.messages_written

    def write(self, vehicle_id: str, topic: str, message: Message) -> None:
        with self._lock:
            recorder = self._recorder
        if recorder is not None:
            recorder.write(self._layout.topic(vehicle_id, topic), message)
