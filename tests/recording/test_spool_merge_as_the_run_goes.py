"""A recorded run's spools are merged into its recording while its processes still write them (SpoolMerge), in the
order a merge of the finished files gives, so that a stop has only the last moments left to merge."""

import random

from coopdrive.bus.publish_spool import PublishSpool
from coopdrive.recording.spool_merge import SPOOL_SUFFIX, SpoolMerge, merge_spools
from coopdrive.v1 import sim_pb2

STEP_S = 0.01


def ground_truth(time_s: float) -> sim_pb2.GroundTruth:
    message = sim_pb2.GroundTruth()
    message.header.sent_time_s = time_s
    return message


def spool_one(spool: PublishSpool, key: str, time_s: float) -> None:
    message = ground_truth(time_s)
    spool.write(key, message, message.SerializeToString())


def taken_by(merge_target: list) -> SpoolMerge:
    return SpoolMerge(lambda key, message: merge_target.append((key, round(message.header.sent_time_s, 6))))


def test_messages_are_written_while_every_spool_still_grows_and_held_back_by_one_that_has_nothing_new(tmp_path):
    taken = []
    merge = taken_by(taken)
    paths = [tmp_path / f"v{number}-group-0{SPOOL_SUFFIX}" for number in (1, 2)]
    for path in paths:
        merge.add(path)
    v1, v2 = PublishSpool(paths[0]), PublishSpool(paths[1])
    for step in range(10):
        spool_one(v1, "coopdrive/v1/x", step * STEP_S)
        spool_one(v2, "coopdrive/v2/x", step * STEP_S)
    merge.step()
    # v2's last waits: v1, whose messages of one time go first, may still write one of that time.
    assert len(taken) == 19 and taken[-1] == ("coopdrive/v1/x", 0.09)
    spool_one(v1, "coopdrive/v1/x", 10 * STEP_S)
    merge.step()
    # Now v1's last waits: v2 has no next message yet, and it may still be earlier.
    assert len(taken) == 20 and taken[-1] == ("coopdrive/v2/x", 0.09)
    merge.writer_gone(paths[1])
    merge.step()
    assert len(taken) == 21 and taken[-1] == ("coopdrive/v1/x", 0.1)
    stats = merge.finish()
    assert (stats.spools, stats.messages, stats.cut_spools) == (2, 21, [])


def test_a_spool_that_has_not_been_created_holds_the_merge_back_until_its_process_is_gone(tmp_path):
    taken = []
    merge = taken_by(taken)
    written, never = tmp_path / f"v1-group-0{SPOOL_SUFFIX}", tmp_path / f"v2-group-0{SPOOL_SUFFIX}"
    merge.add(written)
    merge.add(never)
    spool = PublishSpool(written)
    for step in range(3):
        spool_one(spool, "coopdrive/v1/x", step * STEP_S)
    merge.step()
    assert taken == []
    merge.finish()
    assert [time_s for _, time_s in taken] == [0.0, 0.01, 0.02]


def test_read_in_pieces_cut_anywhere_the_merge_writes_what_a_merge_of_the_finished_files_writes(tmp_path):
    finished_dir, growing_dir = tmp_path / "finished", tmp_path / "growing"
    growing_dir.mkdir()
    rng = random.Random(7)
    spools = {name: PublishSpool(finished_dir / f"{name}{SPOOL_SUFFIX}") for name in ("v1-group-0", "world-sim-0")}
    for step in range(300):
        for name, spool in spools.items():
            # A group's services step apart, so its spool is out of time order by a step or two, as a real one is.
            spool_one(spool, f"coopdrive/{name}/x", max(0, step + rng.choice((-2, -1, 0))) * STEP_S)
    expected = []
    merge_spools(finished_dir, lambda key, message: expected.append((key, round(message.header.sent_time_s, 6))))
    taken = []
    merge = taken_by(taken)
    files = {path.name: path.read_bytes() for path in finished_dir.iterdir()}
    read_up_to = dict.fromkeys(files, 0)
    for name in files:
        merge.add(growing_dir / name)
    while any(read_up_to[name] < len(data) for name, data in files.items()):
        for name, data in files.items():
            piece = data[read_up_to[name]:read_up_to[name] + rng.randint(0, 700)]
            read_up_to[name] += len(piece)
            with open(growing_dir / name, "ab") as file:
                file.write(piece)
        merge.step()
    assert len(taken) > 0.9 * len(expected)  # most were written before the end
    merge.finish()
    assert taken == expected and len(expected) == 600
