"""SpoolTail: one process's spool (coopdrive/bus/publish_spool.py) read while its process still writes it.

Each read gives the messages of the whole records written since the read before; a record still being written is
left for the next read. Once the process has ended, `close_out` says whether its spool ends in a cut record.
"""

from __future__ import annotations

import io
import logging
import struct
from pathlib import Path
from typing import NamedTuple

from mcap.exceptions import EndOfFile, McapError
from mcap.records import Channel, Schema
from mcap.records import Message as McapMessage
from mcap.stream_reader import MAGIC_SIZE, StreamReader

log = logging.getLogger(__name__)

# An MCAP record: its opcode (1 byte), its length (8 bytes, little-endian), then that many bytes.
RECORD_PREFIX_BYTES = 9


class SpooledMessage(NamedTuple):
    """Ordered as a recording orders its messages: by time, then by spool name, then as the process sent them."""
    time_ns: int
    spool_name: str
    sequence: int
    key: str
    type_name: str
    payload: bytes


class SpoolTail:
    def __init__(self, path: Path):
        self.path = path
        self.name = path.name
        self._read_bytes = 0  # up to the end of the last whole record read
        self._records = 0
        self._type_names: dict[int, str] = {}
        self._channels: dict[int, tuple[str, str]] = {}
        # Why the rest of the spool is left out, once a record in it could not be read.
        self.unreadable: str | None = None

    def read_new(self) -> list[SpooledMessage]:
        """The messages of the whole records written since the last read (none while the file does not exist)."""
        if self.unreadable is not None:
            return []
        try:
            with open(self.path, "rb") as file:
                file.seek(self._read_bytes)
                written = file.read()
        except FileNotFoundError:
            return []  # its process has not published yet
        first_read = self._read_bytes == 0
        whole_end = _whole_records_end(written, MAGIC_SIZE if first_read else 0)
        if whole_end == 0:
            return []
        messages = self._parsed(io.BytesIO(written[:whole_end]), skip_magic=not first_read)
        if self.unreadable is None:
            self._read_bytes += whole_end
        return messages

    def close_out(self) -> bool:
        """Called once its process has ended and every whole record is read: True (with a warning) if the spool ends
        in a cut record, as one left by a process killed while writing it."""
        if self.unreadable is not None:
            return True
        try:
            size = self.path.stat().st_size
        except FileNotFoundError:
            return False  # its process ended before it published
        if size > self._read_bytes and not (self._read_bytes == 0 and size <= MAGIC_SIZE):
            log.warning("recording: %s ends in a cut record (its process was killed while writing)", self.name)
            return True
        return False

    def _parsed(self, stream: io.BytesIO, skip_magic: bool) -> list[SpooledMessage]:
        messages: list[SpooledMessage] = []
        try:
            for record in StreamReader(stream, skip_magic=skip_magic).records:
                self._records += 1
                if isinstance(record, Schema):
                    self._type_names[record.id] = record.name
                elif isinstance(record, Channel):
                    self._channels[record.id] = (record.topic, self._type_names.get(record.schema_id, ""))
                elif isinstance(record, McapMessage):
                    key, type_name = self._channels[record.channel_id]
                    messages.append(SpooledMessage(record.log_time, self.name, self._records, key, type_name,
                                                   record.data))
        except EndOfFile:
            pass  # the end of the whole records given
        except (McapError, KeyError, ValueError, struct.error) as error:
            self.unreadable = f"{type(error).__name__}: {error}"
            log.warning("recording: %s is unreadable after %d bytes, the rest left out: %s", self.name,
                        self._read_bytes, self.unreadable)
        return messages


def _whole_records_end(written: bytes, start: int) -> int:
    """Where the last whole record in `written` (records from `start`) ends; 0 if none is whole."""
    end = position = start
    while position + RECORD_PREFIX_BYTES <= len(written):
        record_end = position + RECORD_PREFIX_BYTES + int.from_bytes(written[position + 1:position + 9], "little")
        if record_end > len(written):
            break
        end = position = record_end
    return end if end > start else 0
