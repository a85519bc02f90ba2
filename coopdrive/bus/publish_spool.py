"""PublishSpool: what one process of a recorded run publishes, written to a file of its own as it is sent.

A run's recording used to be every message taken off the bus by a subscriber in the launcher, and two 8-stack
runs side by side on two cores sometimes lost about 10 s of every message from it while the runs went on (the cause
was not established). Written where it is published, a message cannot be lost on its way to the recorder, and the
bus no longer carries every message a second time. After the run the launcher merges the spools into the
recording (spool_merge.py).

A spool is an MCAP file without chunks, each message written through at once: a process killed mid-run
(a service_crash fault) leaves every message it had sent, and a reader of the spool stops at the last whole record.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

from google.protobuf.message import Message
from mcap.writer import IndexType, Writer
from mcap_protobuf.schema import register_schema

# The spool file a process of a recorded run writes; the launcher sets it for each process it starts.
SPOOL_PATH_ENV = "COOPDRIVE_RECORD_SPOOL"
NANOSECONDS = 1_000_000_000
PROTOBUF_ENCODING = "protobuf"


def message_time_ns(message: Message) -> int:
    """A message's time for a recording: its header's sent time (simulated time in a lockstep run); 0 without."""
    header = getattr(message, "header", None)
    if header is None:
        return 0
    return max(0, int(round(header.sent_time_s * NANOSECONDS)))


def is_recorded(key: str) -> bool:
    """Traffic is recorded. Liveliness tokens and _info answers ("/_" parts) are not, nor what goes on verbatim
    chunks ("/@"), which a recorder subscribed to all keys never received: the step markers, and the lockstep
    clocks that world/clock repeats."""
    return "/_" not in key and "/@" not in key


class PublishSpool:
    def __init__(self, path: Path):
        path.parent.mkdir(parents=True, exist_ok=True)
        self.path = path
        self._file = open(path, "wb")
        self._writer = Writer(self._file, use_chunking=False, index_types=IndexType.NONE, use_statistics=False,
                              use_summary_offsets=False)
        self._writer.start(profile=PROTOBUF_ENCODING, library="coopdrive publish spool")
        self._file.flush()
        self._channels: dict[str, int] = {}
        self._schemas: dict[type, int] = {}
        self._lock = threading.Lock()

    def write(self, key: str, message: Message, payload: bytes) -> None:
        """`payload`: the message as it was serialised for the bus."""
        if not is_recorded(key):
            return
        time_ns = message_time_ns(message)
        with self._lock:
            channel_id = self._channels.get(key)
            if channel_id is None:
                channel_id = self._channel(key, type(message))
            self._writer.add_message(channel_id, log_time=time_ns, data=payload, publish_time=time_ns)
            self._file.flush()

    def _channel(self, key: str, message_type: type) -> int:
        schema_id = self._schemas.get(message_type)
        if schema_id is None:
            schema_id = self._schemas[message_type] = register_schema(self._writer, message_type)
        channel_id = self._channels[key] = self._writer.register_channel(key, PROTOBUF_ENCODING, schema_id)
        return channel_id


_process_spool: PublishSpool | None = None
_looked_up = False
_lookup_lock = threading.Lock()


def process_spool() -> PublishSpool | None:
    """This process's spool when the launcher asked for one (SPOOL_PATH_ENV), shared by all its buses."""
    global _process_spool, _looked_up
    if not _looked_up:
        with _lookup_lock:
            if not _looked_up:
                path = os.environ.get(SPOOL_PATH_ENV)
                _process_spool = PublishSpool(Path(path)) if path else None
                _looked_up = True
    return _process_spool
