"""McapRecorder: writes protobuf messages to MCAP with their schemas, safe to call from many threads.

Every recording also carries the channels Foxglove draws (coopdrive.visual), derived from the messages as they
are written, so any MCAP the stack writes opens in Foxglove with its map, 3D view and plots.
"""

from __future__ import annotations

import json
import logging
import queue
import threading
from pathlib import Path
from typing import Callable

from google.protobuf.message import Message
from mcap_protobuf.writer import Writer

from coopdrive.bus.publish_spool import message_time_ns
from coopdrive.roadmap import RoadMap
from coopdrive.visual import VisualChannels, recorded_road_map
from coopdrive.visual.channels import RECORDING_REORDER_S

log = logging.getLogger(__name__)
CONFIG_METADATA = "coopdrive.config"
# mcap's own: a chunk is written to the file when it holds this much.
DEFAULT_CHUNK_BYTES = 1024 * 1024
# A recorder on a vehicle may die with the power: what it loses is the chunk it was filling, here about half a
# second of a vehicle's bus (a stack's 20 s of an 8-stack run: 3.9 MB) where 1 MiB chunks lose five; the file grows
# by 3 % (4.01 against 3.89 MB for those 20 s).
LIVE_CHUNK_BYTES = 128 * 1024


class McapRecorder:
    def __init__(self, path: str | Path, metadata: dict[str, dict[str, str]] | None = None,
                 road_map: RoadMap | None = None, visuals: bool = True, chunk_bytes: int = DEFAULT_CHUNK_BYTES,
                 on_failure: Callable[[OSError], None] | None = None):
        """road_map: the lane map the Foxglove channels draw (default: the one the configs in `metadata` name).
        visuals: False writes the messages alone. chunk_bytes: how much a chunk holds before it goes to the file,
        which is also what a recording cut short (killed, without power) loses at most. on_failure(error): the
        file could not be written (a full disk): the recorder has stopped, said so in one line, and writes no
        more; what it wrote before reads back as a cut recording."""
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._file = open(self.path, "wb")
        self._writer = Writer(self._file, chunk_size=chunk_bytes)
        self._lock = threading.Lock()
        self._closed = False
        self._on_failure = on_failure
        self.failure: OSError | None = None
        self.messages_written = 0
        for name, values in (metadata or {}).items():
            self.add_metadata(name, values)
        if road_map is None:
            road_map = recorded_road_map((metadata or {}).get(CONFIG_METADATA, {}))
        self._visuals = (VisualChannels(self._write_visual, road_map, reorder_s=RECORDING_REORDER_S) if visuals
                         else None)
        # Derived on a thread of their own: a live recorder stamps each message's arrival in the bus's callback,
        # which must not wait for the scene drawn from the one before.
        self._to_derive: queue.SimpleQueue = queue.SimpleQueue()
        self._deriver = threading.Thread(target=self._derive, name="mcap-visuals", daemon=True)
        if self._visuals is not None:
            self._deriver.start()

    def learn_config(self, participant: str, config_json: str) -> None:
        """A live service's config (ServiceConfigCollector), written at once: a recording cut short (a recorder
        killed, the power gone) keeps the configs learned before the cut, and replay reads them. Geolocation's
        names the lane map to draw."""
        self.add_configs({participant: config_json})
        if self._visuals is not None and participant.endswith("/geolocation"):
            road_map = recorded_road_map({participant: config_json})
            with self._lock:
                self._visuals.road_map = road_map

    def add_configs(self, configs: dict[str, str]) -> None:
        """Every service's config ("<vehicle>/<service>" -> JSON), as replay and scoring read them back."""
        for name, values in config_metadata(configs).items():
            self.add_metadata(name, values)

    def add_metadata(self, name: str, values: dict[str, str]) -> None:
        """Written to the file at once (outside the chunk being filled), not kept to the end."""
        with self._lock:
            if self._closed or self.failure is not None:
                return
            try:
                self._writer.add_metadata(name, values)
                self._file.flush()
            except OSError as error:
                self._fail(error)

    def write(self, topic: str, message: Message, log_time_ns: int | None = None) -> None:
        """log_time_ns: when the message arrived (a live recorder's clock); publish time is its header's sent time.
        Without it both are the sent time (a lockstep run, where the simulated time is the only clock)."""
        time_ns = message_time_ns(message)
        log_time_ns = time_ns if log_time_ns is None else log_time_ns
        with self._lock:
            if self._closed or self.failure is not None:
                return
            try:
                self._writer.write_message(topic, message, log_time=log_time_ns, publish_time=time_ns)
            except OSError as error:
                self._fail(error)
                return
            self.messages_written += 1
        if self._visuals is not None and self._visuals.draws(topic):
            self._to_derive.put((topic, message, log_time_ns))

    def _derive(self) -> None:
        # Only this thread feeds the visual channels, so they need no lock; the file does, for each write alone: a
        # scene drawn while holding it would keep the bus's messages waiting.
        while (item := self._to_derive.get()) is not None:
            self._visuals.on_message(*item)
        self._visuals.flush()  # the last step's

    def _write_visual(self, topic: str, message: Message, time_ns: int) -> None:
        """Called by the visual channels on the deriving thread, at the log time of the message they came from."""
        with self._lock:
            if self.failure is not None:
                return
            try:
                self._writer.write_message(topic, message, log_time=time_ns, publish_time=time_ns)
            except OSError as error:
                self._fail(error)

    def close(self) -> None:
        if self._deriver.is_alive():
            self._to_derive.put(None)  # after every message written so far
            self._deriver.join()
        with self._lock:
            if self._closed:
                return
            self._closed = True
            try:
                if self.failure is None:
                    self._writer.finish()
                self._file.close()
            except OSError as error:
                if self.failure is None:
                    self._fail(error)

    def _fail(self, error: OSError) -> None:
        """Called holding the lock: once, and the recorder writes nothing more (a full disk would otherwise fail
        every message of the bus, each with its own traceback)."""
        self.failure = error
        log.error("%s: recording stopped: %s; what was written before reads back as a cut recording", self.path,
                  " ".join(str(error).split()))
        if self._on_failure is not None:
            self._on_failure(error)


def config_metadata(configs: dict[str, str]) -> dict[str, dict[str, str]]:
    """Service configs as MCAP metadata: {"coopdrive.config": {"<vehicle>/<service>": json}}."""
    return {CONFIG_METADATA: {key: value if isinstance(value, str) else json.dumps(value)
                              for key, value in configs.items()}}
