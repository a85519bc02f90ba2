"""`coopdrive record`: writes everything on a live bus to MCAP until SIGINT or SIGTERM (or for a duration).

A replayable recording: each message's MCAP log time is when it arrived here (its publish time the sender's
header.sent_time_s), and the effective config of every service seen on the bus goes into the metadata as
`run --record` stores it, as soon as it is seen, so `coopdrive replay` can run any of them again over the drive,
even out of a recording cut short by a kill or a power loss (reader.py reads such a file up to the cut).
"""

from __future__ import annotations

import datetime as dt
import signal
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from coopdrive.bus import Bus, BusConfig
from coopdrive.recording.live_configs import ServiceConfigCollector
from coopdrive.bus.publish_spool import is_recorded
from coopdrive.recording.writer import LIVE_CHUNK_BYTES, McapRecorder
from coopdrive.runtime.signal_wait import wait_hearing_signals


def recording_path(text: str | Path) -> Path:
    """A folder (existing, or written with a trailing slash) gets a file named after the UTC start time."""
    path = Path(text)
    if path.is_dir() or str(text).endswith("/"):
        return path / f"drive-{dt.datetime.now(dt.timezone.utc):%Y%m%d-%H%M%S}.mcap"
    return path


@dataclass(frozen=True)
class LiveRecording:
    path: Path
    messages: int
    services: list[str]  # whose configs it stored
    failure: OSError | None = None  # the file could not be written (a full disk): the recording stopped there


def record_live(path: str | Path, connect: list[str], key_expr: str = "coopdrive/**",
                duration_s: float | None = None, zenoh_config: str | None = None,
                vehicle_id: str = "*") -> LiveRecording:
    """Records until a signal, the duration, or a file that cannot be written any more. `zenoh_config`: the
    recorder's Zenoh config (a vehicle's bus credentials); `vehicle_id`: whose services' configs it asks."""
    stop = threading.Event()
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, lambda *_: stop.set())
    path = recording_path(path)
    bus = Bus(BusConfig(connect=connect, zenoh_config_file=zenoh_config))
    recorder = McapRecorder(path, chunk_bytes=LIVE_CHUNK_BYTES, on_failure=lambda _: stop.set())
    configs = ServiceConfigCollector(bus, recorder.learn_config, vehicle_id)

    def on_message(key: str, message) -> None:
        if is_recorded(key):
            recorder.write(key, message, log_time_ns=time.time_ns())

    bus.subscribe_key(key_expr, on_message)
    configs.start()
    try:
        wait_hearing_signals(stop, duration_s)
    finally:
        found = configs.stop()  # asks once more: a config first seen or changed now is written too
        bus.close()
        recorder.close()
    return LiveRecording(path, recorder.messages_written, sorted(found), recorder.failure)
