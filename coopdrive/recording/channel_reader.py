"""The messages of a few channels of an indexed MCAP file, read through the file's message indexes.

mcap's own reader parses every record of every chunk it opens and drops the channels not asked for; a replay of
one service of an 8-vehicle run asks for about a tenth of them. Each chunk ends in one MessageIndex record per
channel, listing where in the chunk's records that channel's messages start, and the summary's ChunkIndex says
where those indexes are: so only the asked channels' messages are parsed (with mcap's record classes), and chunks
holding none of them are not read. The order is mcap's log-time order: by log time, then by chunk offset, then by
place in the chunk (mcap.reader.SeekingReader.iter_messages with log_time_order=True).
"""

from __future__ import annotations

import heapq
import io
from typing import IO, Iterator

from mcap.reader import Summary
from mcap.records import Chunk, ChunkIndex, Message, MessageIndex
from mcap.data_stream import ReadDataStream
from mcap.stream_reader import get_chunk_data_stream

# A record: opcode (1 byte) and content length (8 bytes), then the content.
_RECORD_PREFIX_BYTES = 9
# The place in a chunk given to the chunk itself in the queue: before any of its messages.
_CHUNK_ITSELF = -1


def indexes_every_chunk(summary: Summary | None) -> bool:
    """Whether the file's chunks can be read this way: chunked, and each chunk with its message indexes."""
    return bool(summary is not None and summary.chunk_indexes
                and all(index.message_index_offsets for index in summary.chunk_indexes))


def channel_messages(stream: IO[bytes], summary: Summary, channel_ids: set[int], start_ns: int | None = None,
                     end_ns: int | None = None) -> Iterator[Message]:
    """The messages of channel_ids with log times from start_ns and before end_ns, in mcap's log-time order."""
    queue: list[tuple[int, int, int, ChunkIndex | Message]] = []
    for chunk_index in summary.chunk_indexes:
        if channel_ids.isdisjoint(chunk_index.message_index_offsets):
            continue
        if (start_ns is not None and chunk_index.message_end_time < start_ns) or (
                end_ns is not None and chunk_index.message_start_time >= end_ns):
            continue
        queue.append((chunk_index.message_start_time, chunk_index.chunk_start_offset, _CHUNK_ITSELF, chunk_index))
    heapq.heapify(queue)
    while queue:
        _, _, place, item = heapq.heappop(queue)
        if place != _CHUNK_ITSELF:
            yield item
            continue
        for place, message in _chunk_messages(stream, item, channel_ids, start_ns, end_ns):
            heapq.heappush(queue, (message.log_time, item.chunk_start_offset, place, message))


def _chunk_messages(stream: IO[bytes], chunk_index: ChunkIndex, channel_ids: set[int], start_ns: int | None,
                    end_ns: int | None) -> list[tuple[int, Message]]:
    """(offset in the chunk's records, message) of the wanted channels in one chunk, by offset."""
    offsets = []
    for channel_id, index_offset in chunk_index.message_index_offsets.items():
        if channel_id in channel_ids:
            stream.seek(index_offset + _RECORD_PREFIX_BYTES, io.SEEK_SET)
            offsets += [offset for log_time, offset in MessageIndex.read(ReadDataStream(stream)).records
                        if (start_ns is None or log_time >= start_ns) and (end_ns is None or log_time < end_ns)]
    if not offsets:
        return []
    stream.seek(chunk_index.chunk_start_offset + _RECORD_PREFIX_BYTES, io.SEEK_SET)
    records, _ = get_chunk_data_stream(Chunk.read(ReadDataStream(stream)))
    messages = []
    for offset in sorted(offsets):
        records.read(offset - records.count)  # the records of other channels, unparsed
        records.read1()  # the opcode: a message, as the index says
        messages.append((offset, Message.read(records, records.read8())))
    return messages
