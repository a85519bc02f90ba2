"""Reads an MCAP recording back into (topic, message) pairs in log-time order."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Iterator

from google.protobuf.message import Message
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from coopdrive.bus.type_registry import message_class


@dataclass(frozen=True)
class RecordedMessage:
    topic: str
    log_time_ns: int
    message: Message


def read_messages(path: str | Path, topics: Iterable[str] | None = None) -> Iterator[RecordedMessage]:
    """Messages decoded into coopdrive's own generated classes (so they compare equal to live ones); topics: only
    those channels' (the others are neither decoded nor put in time order, which is most of a reading's cost)."""
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        wanted = None if topics is None else list(topics)
        for schema, channel, message in reader.iter_messages(topics=wanted, log_time_order=True):
            cls = message_class(schema.name if schema else None)
            if cls is None:
                continue
            decoded = cls()
            decoded.ParseFromString(message.data)
            yield RecordedMessage(channel.topic, message.log_time, decoded)


def read_metadata(path: str | Path) -> dict[str, dict[str, str]]:
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        return {record.name: dict(record.metadata) for record in reader.iter_metadata()}


def recorded_topics(path: str | Path) -> list[str]:
    """The topics of the recording's channels, from its summary (or, without one, from reading it through)."""
    with open(path, "rb") as stream:
        summary = make_reader(stream).get_summary()
    if summary is None:
        return sorted({recorded.topic for recorded in read_messages(path)})
    return sorted({channel.topic for channel in summary.channels.values()})
