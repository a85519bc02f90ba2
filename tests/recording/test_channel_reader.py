"""Reading some channels of an MCAP file through its message indexes (coopdrive/recording/channel_reader.py) gives
what mcap's own reader gives: the same messages in the same order, for any channels and any time window."""

import io

from hypothesis import given, settings
from hypothesis import strategies as st
from mcap.reader import make_reader
from mcap.writer import CompressionType, IndexType, Writer

from coopdrive.recording.channel_reader import channel_messages, indexes_every_chunk
from coopdrive.recording.reader import read_messages
from coopdrive.recording.writer import McapRecorder
from coopdrive.v1 import ego_pb2

CHANNELS = 4
# (channel, log time): times repeat and go back, so chunks overlap in time and one instant holds several messages.
MESSAGES = st.lists(st.tuples(st.integers(0, CHANNELS - 1), st.integers(0, 40)), min_size=1, max_size=120)


def mcap_file(messages: list[tuple[int, int]], chunk_bytes: int, compression: CompressionType,
              index_types: IndexType = IndexType.ALL) -> io.BytesIO:
    stream = io.BytesIO()
    writer = Writer(stream, chunk_size=chunk_bytes, compression=compression, index_types=index_types)
    writer.start()
    schema = writer.register_schema("raw", "none", b"")
    channels = [writer.register_channel(f"topic{k}", "none", schema) for k in range(CHANNELS)]
    for sequence, (channel, log_time) in enumerate(messages):
        writer.add_message(channels[channel], log_time, f"{channel}:{sequence}".encode(), log_time, sequence)
    writer.finish()
    stream.seek(0)
    return stream


def through_mcap(stream: io.BytesIO, topics: list[str], start_ns, end_ns) -> list[tuple[int, int, bytes]]:
    stream.seek(0)
    return [(message.channel_id, message.log_time, message.data) for _, _, message in make_reader(stream).iter_messages(
        topics=topics, starting_at=start_ns, ending_before=end_ns, log_time_order=True)]


def through_the_indexes(stream: io.BytesIO, topics: list[str], start_ns, end_ns) -> list[tuple[int, int, bytes]]:
    stream.seek(0)
    summary = make_reader(stream).get_summary()
    assert indexes_every_chunk(summary)
    ids = {channel_id for channel_id, channel in summary.channels.items() if channel.topic in topics}
    return [(message.channel_id, message.log_time, message.data)
            for message in channel_messages(stream, summary, ids, start_ns, end_ns)]


@settings(max_examples=60, deadline=None)
@given(messages=MESSAGES, chunk_bytes=st.sampled_from([40, 200, 1 << 20]),
       compression=st.sampled_from(list(CompressionType)),
       channels=st.sets(st.integers(0, CHANNELS - 1), min_size=1),
       window=st.tuples(st.none() | st.integers(0, 20), st.none() | st.integers(20, 40)))
def test_the_channels_read_through_the_indexes_are_mcap_s_messages_in_mcap_s_order(messages, chunk_bytes, compression,
                                                                                    channels, window):
    stream = mcap_file(messages, chunk_bytes, compression)
    topics = [f"topic{k}" for k in sorted(channels)]
    assert through_the_indexes(stream, topics, *window) == through_mcap(stream, topics, *window)


def test_a_file_without_message_indexes_is_not_read_through_them():
    stream = mcap_file([(0, 1), (1, 2)], 40, CompressionType.ZSTD, IndexType.CHUNK)
    assert not indexes_every_chunk(make_reader(stream).get_summary())


def test_a_recording_of_many_vehicles_reads_back_one_vehicle_s_messages_in_time_order(tmp_path):
    path = tmp_path / "run.mcap"
    recorder = McapRecorder(path, visuals=False, chunk_bytes=256)
    for step in range(50):
        for vehicle in ("v1", "v2", "v3"):
            state = ego_pb2.EgoState(speed_mps=step, x_m=float(vehicle[1]))
            state.header.sample_time_s = state.header.sent_time_s = 0.02 * step
            recorder.write(f"coopdrive/{vehicle}/ego/state", state)
    recorder.close()
    read = list(read_messages(path, ["coopdrive/v2/ego/state"]))
    assert [item.message.speed_mps for item in read] == list(range(50))
    assert {item.message.x_m for item in read} == {2.0}
    assert [item.log_time_ns for item in read] == sorted(item.log_time_ns for item in read)
