"""`coopdrive record`: writes everything on a live bus to MCAP until SIGINT or SIGTERM."""

from __future__ import annotations

import signal
import threading
from pathlib import Path

from coopdrive.bus import Bus, BusConfig
from coopdrive.recording.writer import McapRecorder


def record_live(path: Path, connect: list[str], key_expr: str = "coopdrive/**") -> int:
    stop = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.set())
    bus = Bus(BusConfig(connect=connect))
    recorder = McapRecorder(path)
    bus.subscribe_key(key_expr, lambda key, message: None if "/_" in key else recorder.write(key, message))
    try:
        stop.wait()
    finally:
        bus.close()
        recorder.close()
    return recorder.messages_written
