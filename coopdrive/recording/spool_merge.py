"""The spools a recorded run's processes wrote (coopdrive/bus/publish_spool.py), merged into its recording in time order.

Messages of one time keep a fixed order, by the spool's name (the launcher names each after its process) and then
as the process sent them, so a recording's order does not depend on when its messages arrived anywhere.
"""

from __future__ import annotations

import heapq
import logging
import mmap
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterator, NamedTuple

from google.protobuf.message import DecodeError, Message
from mcap.exceptions import EndOfFile, McapError
from mcap.records import Channel, Schema
from mcap.records import Message as McapMessage
from mcap.stream_reader import StreamReader

from coopdrive.bus.type_registry import message_class

log = logging.getLogger(__name__)

SPOOL_SUFFIX = ".spool.mcap"


class SpooledMessage(NamedTuple):
    time_ns: int
    spool_index: int
    sequence: int
    key: str
    type_name: str
    payload: bytes


@dataclass
class SpoolMergeStats:
    spools: int = 0
    messages: int = 0
    # Messages left out, each with a warning: a type this build does not know, or bytes that do not parse.
    unreadable: int = 0
    # Spools whose last record was cut short (a process killed while writing it).
    cut_spools: list[str] = field(default_factory=list)


def spool_paths(spool_dir: Path) -> list[Path]:
    return sorted(spool_dir.glob(f"*{SPOOL_SUFFIX}"))


def merge_spools(spool_dir: Path, write: Callable[[str, Message], None]) -> SpoolMergeStats:
    """Calls write(key, message) for every spooled message of the run, in time order."""
    stats = SpoolMergeStats()
    paths = spool_paths(spool_dir)
    stats.spools = len(paths)
    streams = [_spooled(path, index, stats) for index, path in enumerate(paths)]
    for spooled in heapq.merge(*streams):
        message = _decoded(spooled)
        if message is None:
            stats.unreadable += 1
            continue
        write(spooled.key, message)
        stats.messages += 1
    return stats


def _decoded(spooled: SpooledMessage) -> Message | None:
    cls = message_class(spooled.type_name)
    if cls is None:
        log.warning("recording: left out a message on %s of unknown type %r", spooled.key, spooled.type_name)
        return None
    message = cls()
    try:
        message.ParseFromString(spooled.payload)
    except DecodeError as error:
        log.warning("recording: left out a malformed %s on %s: %s", spooled.type_name, spooled.key, error)
        return None
    return message


def _spooled(path: Path, index: int, stats: SpoolMergeStats) -> Iterator[SpooledMessage]:
    """A spool's messages as written; a spool is never finished, so it ends at the end of its file."""
    with open(path, "rb") as file:
        if os.fstat(file.fileno()).st_size == 0:
            return  # its process was killed before it wrote a byte
        # Mapped, not read: a file's tell() at every record is a system call, which hands the interpreter's lock to
        # the recorder's drawing thread and waits to get it back (a third of the merge's time); the map's is not.
        with mmap.mmap(file.fileno(), 0, access=mmap.ACCESS_READ) as stream:
            yield from _records(stream, path.name, index, stats)


def _records(stream: mmap.mmap, name: str, index: int, stats: SpoolMergeStats) -> Iterator[SpooledMessage]:
    type_names: dict[int, str] = {}
    channels: dict[int, tuple[str, str]] = {}
    whole_bytes = 0
    try:
        for sequence, record in enumerate(StreamReader(stream).records):
            whole_bytes = stream.tell()
            if isinstance(record, Schema):
                type_names[record.id] = record.name
            elif isinstance(record, Channel):
                channels[record.id] = (record.topic, type_names.get(record.schema_id, ""))
            elif isinstance(record, McapMessage):
                key, type_name = channels[record.channel_id]
                yield SpooledMessage(record.log_time, index, sequence, key, type_name, record.data)
    except EndOfFile:
        if stream.tell() > whole_bytes:
            stats.cut_spools.append(name)
            log.warning("recording: %s ends in a cut record (its process was killed while writing)", name)
    except (McapError, KeyError) as error:
        stats.cut_spools.append(name)
        log.warning("recording: %s is unreadable after %d bytes, the rest left out: %s", name, whole_bytes, error)
