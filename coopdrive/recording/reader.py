"""Reads an MCAP recording back into (topic, message) pairs in log-time order, its metadata and its topics.

A recording cut while it was written (a recorder killed, a vehicle's power gone) has no index at its end. Such a
file is read from the start up to its last whole record instead, with one warning saying how much was read:
everything before the cut is there, whatever came after the writer's last whole chunk is lost.
"""

from __future__ import annotations

import functools
import logging
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Iterator

from google.protobuf.message import Message
from mcap.exceptions import McapError
from mcap.reader import Summary, make_reader
from mcap.records import Channel, Metadata, Schema
from mcap.records import Message as McapMessage
from mcap.stream_reader import StreamReader
from mcap.writer import MCAP0_MAGIC

from coopdrive.bus.type_registry import message_class
from coopdrive.recording.channel_reader import channel_messages, indexes_every_chunk
from coopdrive.bus.publish_spool import NANOSECONDS

_log = logging.getLogger(__name__)
# What a file cut inside a record, or not MCAP at all, raises while it is read.
_UNREADABLE = (McapError, struct.error, ValueError)


class RecordingError(ValueError):
    """The file is not an MCAP recording at all (or cannot be opened)."""

    def __init__(self, path: str | Path, reason: object) -> None:
        super().__init__(f"{path}: not a readable MCAP recording ({' '.join(str(reason).split())})")


@dataclass(frozen=True)
class RecordedMessage:
    topic: str
    log_time_ns: int
    message: Message


def read_messages(path: str | Path, topics: Iterable[str] | None = None, start_ns: int | None = None,
                  end_ns: int | None = None) -> Iterator[RecordedMessage]:
    """Messages decoded into coopdrive's own generated classes (so they compare equal to live ones); topics: only
    those channels' (the others are neither decoded nor put in time order, which is most of a reading's cost);
    start_ns, end_ns: only log times from start_ns and before end_ns (the index skips the chunks outside)."""
    wanted = None if topics is None else list(topics)
    if _is_cut(path):
        records = _messages_of_cut(path, wanted, start_ns, end_ns)
    else:
        records = _indexed_messages(path, wanted, start_ns, end_ns)
    for channel, message in records:
        cls = message_class(channel.schema_name)
        if cls is None:
            continue
        decoded = cls()
        decoded.ParseFromString(message.data)
        yield RecordedMessage(channel.topic, message.log_time, decoded)


def read_metadata(path: str | Path) -> dict[str, dict[str, str]]:
    """Metadata by name; records of one name are merged in file order (a live recorder writes each service's
    config as it learns it, so that a recording cut short still has the configs learned before the cut)."""
    merged: dict[str, dict[str, str]] = {}
    for record in _read_cut(path).metadata if _is_cut(path) else _indexed_metadata(path):
        merged.setdefault(record.name, {}).update(record.metadata)
    return merged


def recording_start_ns(path: str | Path) -> int | None:
    """The log time of the recording's first message (None: it holds none)."""
    summary = _summary(path)
    if summary is not None and summary.statistics is not None:
        return summary.statistics.message_start_time if summary.statistics.message_count else None
    return min((message.log_time for _, message in _raw_messages(path)), default=None)


def recorded_topics(path: str | Path) -> list[str]:
    """The topics of the recording's channels."""
    summary = _summary(path)
    if summary is not None:
        return sorted({channel.topic for channel in summary.channels.values()})
    if _is_cut(path):
        return sorted({channel.topic for channel in _read_cut(path).channels.values()})
    return sorted({channel.topic for channel, _ in _raw_messages(path)})


@dataclass(frozen=True)
class _Channel:
    topic: str
    schema_name: str | None


@dataclass
class _CutFile:
    """A cut file's whole records, read in one pass from its start."""

    channels: dict[int, _Channel]
    messages: list[McapMessage]
    metadata: list[Metadata]


@dataclass(frozen=True)
class _End:
    """What the end of an MCAP file holds: its summary (None where the writer wrote none), or nothing readable."""

    cut: bool
    summary: Summary | None = None


def _is_cut(path: str | Path) -> bool:
    """Whether an MCAP file lacks its end (footer and index); RecordingError if it is no MCAP file at all."""
    return _end(path).cut


def _summary(path: str | Path) -> Summary | None:
    return _end(path).summary


def _end(path: str | Path) -> _End:
    """A replay asks for the metadata, the topics, the first time and the messages: the end is read once."""
    try:
        status = Path(path).stat()
    except OSError as error:
        raise RecordingError(path, error) from error
    return _read_end(str(path), status.st_size, status.st_mtime_ns)


@functools.lru_cache(maxsize=4)
def _read_end(path: str, _size: int, _mtime_ns: int) -> _End:
    try:
        with open(path, "rb") as stream:
            if stream.read(len(MCAP0_MAGIC)) != MCAP0_MAGIC:
                raise RecordingError(path, "no MCAP magic at its start")
            stream.seek(0)
            try:
                return _End(cut=False, summary=make_reader(stream).get_summary())
            except _UNREADABLE:
                return _End(cut=True)
    except OSError as error:
        raise RecordingError(path, error) from error


def _raw_messages(path: str | Path) -> Iterator[tuple[_Channel, McapMessage]]:
    """Every message, undecoded."""
    if _is_cut(path):
        cut = _read_cut(path)
        return ((cut.channels[message.channel_id], message) for message in cut.messages)
    return _indexed_messages(path, None, None, None)


def _indexed_messages(path: str | Path, topics: list[str] | None, start_ns: int | None,
                      end_ns: int | None) -> Iterator[tuple[_Channel, McapMessage]]:
    summary = _summary(path)
    if indexes_every_chunk(summary):
        yield from _messages_of_channels(path, summary, topics, start_ns, end_ns)
        return
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        for schema, channel, message in reader.iter_messages(topics=topics, starting_at=start_ns, ending_before=end_ns,
                                                             log_time_order=True):
            yield _Channel(channel.topic, schema.name if schema else None), message


def _messages_of_channels(path: str | Path, summary: Summary, topics: list[str] | None, start_ns: int | None,
                          end_ns: int | None) -> Iterator[tuple[_Channel, McapMessage]]:
    """_indexed_messages through the message indexes: only the records of the topics' channels parsed (every
    channel's where topics is None; channel_reader.py)."""
    wanted = None if topics is None else set(topics)
    channels = {channel_id: _Channel(channel.topic, summary.schemas[channel.schema_id].name
                                     if channel.schema_id in summary.schemas else None)
                for channel_id, channel in summary.channels.items() if wanted is None or channel.topic in wanted}
    with open(path, "rb") as stream:
        for message in channel_messages(stream, summary, set(channels), start_ns, end_ns):
            yield channels[message.channel_id], message


def _indexed_metadata(path: str | Path) -> Iterator[Metadata]:
    with open(path, "rb") as stream:
        yield from make_reader(stream).iter_metadata()


def _read_cut(path: str | Path) -> _CutFile:
    """Every whole record from the start of the file up to the cut, which ends the reading instead of raising.
    A replay asks for the metadata, the topics and the messages: the file is read once for the three."""
    status = Path(path).stat()
    return _read_cut_once(str(path), status.st_size, status.st_mtime_ns)


@functools.lru_cache(maxsize=1)
def _read_cut_once(path: str, _size: int, _mtime_ns: int) -> _CutFile:
    schemas: dict[int, str] = {}
    cut = _CutFile({}, [], [])
    with open(path, "rb") as stream:
        records = StreamReader(stream, skip_magic=False).records
        while True:
            try:
                record = next(records)
            except (StopIteration, *_UNREADABLE):
                return cut
            if isinstance(record, Schema):
                schemas[record.id] = record.name
            elif isinstance(record, Channel):
                cut.channels[record.id] = _Channel(record.topic, schemas.get(record.schema_id))
            elif isinstance(record, McapMessage):
                cut.messages.append(record)
            elif isinstance(record, Metadata):
                cut.metadata.append(record)


def _messages_of_cut(path: str | Path, topics: list[str] | None, start_ns: int | None,
                     end_ns: int | None) -> Iterator[tuple[_Channel, McapMessage]]:
    cut = _read_cut(path)
    messages = sorted(cut.messages, key=lambda m: m.log_time)  # stable: one instant's keep the file's order
    span_s = (messages[-1].log_time - messages[0].log_time) / NANOSECONDS if messages else 0.0
    _log.warning("%s: cut short while it was written (no readable index at its end, as a recorder killed or without "
                 "power leaves it): read %d messages over %.1f s; whatever came after its last whole chunk is lost",
                 path, len(messages), span_s)
    wanted = None if topics is None else set(topics)
    for message in messages:
        channel = cut.channels[message.channel_id]
        in_window = (start_ns is None or message.log_time >= start_ns) and (end_ns is None or message.log_time < end_ns)
        if in_window and (wanted is None or channel.topic in wanted):
            yield channel, message
