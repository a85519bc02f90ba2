"""A recorded run's processes spool what they publish (PublishSpool), and the launcher merges the spools into the
recording (merge_spools): in time order, whole up to a kill, and a bad record costs only itself."""

import logging
import os
import subprocess
import sys
import textwrap

import pytest

from coopdrive.bus.publish_spool import SPOOL_PATH_ENV, PublishSpool, is_recorded
from coopdrive.recording.spool_merge import SPOOL_SUFFIX, merge_spools
from coopdrive.v1 import ego_pb2, sim_pb2

KILLED_AFTER_MESSAGES = 500


def ground_truth(time_s: float) -> sim_pb2.GroundTruth:
    message = sim_pb2.GroundTruth()
    message.header.sent_time_s = time_s
    return message


def spool_in(directory, name: str) -> PublishSpool:
    return PublishSpool(directory / f"{name}{SPOOL_SUFFIX}")


def spool_truth(spool: PublishSpool, key: str, times_s) -> None:
    for time_s in times_s:
        message = ground_truth(time_s)
        spool.write(key, message, message.SerializeToString())


def merged(directory) -> tuple[list[tuple[str, float]], object]:
    taken = []
    stats = merge_spools(directory, lambda key, message: taken.append((key, message.header.sent_time_s)))
    return taken, stats


def test_spools_merge_in_time_order_and_messages_of_one_time_in_the_order_of_the_spools_names(tmp_path):
    later_name, earlier_name = spool_in(tmp_path, "v2-group-0"), spool_in(tmp_path, "v1-group-0")
    spool_truth(later_name, "coopdrive/v2/x", [0.0, 0.1, 0.2])
    spool_truth(earlier_name, "coopdrive/v1/x", [0.05, 0.1, 0.3])
    taken, stats = merged(tmp_path)
    assert taken == [("coopdrive/v2/x", 0.0), ("coopdrive/v1/x", 0.05), ("coopdrive/v1/x", 0.1),
                     ("coopdrive/v2/x", 0.1), ("coopdrive/v2/x", 0.2), ("coopdrive/v1/x", 0.3)]
    assert (stats.spools, stats.messages, stats.unreadable, stats.cut_spools) == (2, 6, 0, [])


def test_a_process_killed_mid_run_leaves_every_message_it_had_sent_in_its_spool(tmp_path):
    program = textwrap.dedent(f"""
        import os, signal
        from coopdrive.bus import Bus  # the bus's put finds the spool the launcher named in the environment
        from coopdrive.bus.publish_spool import process_spool
        from coopdrive.v1 import sim_pb2
        for step in range({KILLED_AFTER_MESSAGES}):
            message = sim_pb2.GroundTruth()
            message.header.sent_time_s = step * 0.01
            process_spool().write("coopdrive/world/ground_truth", message, message.SerializeToString())
        os.kill(os.getpid(), signal.SIGKILL)
    """)
    environment = {**os.environ, SPOOL_PATH_ENV: str(tmp_path / f"world-sim-0{SPOOL_SUFFIX}")}
    finished = subprocess.run([sys.executable, "-c", program], env=environment, timeout=60)
    assert finished.returncode == -9
    taken, stats = merged(tmp_path)
    assert len(taken) == KILLED_AFTER_MESSAGES and stats.cut_spools == []
    assert taken[-1] == ("coopdrive/world/ground_truth", pytest.approx((KILLED_AFTER_MESSAGES - 1) * 0.01))


def test_a_spool_cut_inside_its_last_record_loses_that_record_alone_and_says_which_spool(tmp_path, caplog):
    spool = spool_in(tmp_path, "v1-control-0")
    spool_truth(spool, "coopdrive/v1/x", [0.0, 0.1, 0.2])
    os.truncate(spool.path, spool.path.stat().st_size - 3)
    with caplog.at_level(logging.WARNING):
        taken, stats = merged(tmp_path)
    assert [time_s for _, time_s in taken] == [0.0, 0.1]
    assert stats.cut_spools == [spool.path.name]
    assert f"{spool.path.name} ends in a cut record" in caplog.text


def test_a_message_that_does_not_parse_is_left_out_with_a_warning_and_the_rest_are_kept(tmp_path, caplog):
    spool = spool_in(tmp_path, "v1-geolocation-0")
    spool_truth(spool, "coopdrive/v1/x", [0.0])
    spool.write("coopdrive/v1/ego/state", ego_pb2.EgoState(), b"\xff\xff\xff")
    spool_truth(spool, "coopdrive/v1/x", [0.2])
    with caplog.at_level(logging.WARNING):
        taken, stats = merged(tmp_path)
    assert [time_s for _, time_s in taken] == [0.0, 0.2] and stats.unreadable == 1
    assert "left out a malformed coopdrive.v1.EgoState on coopdrive/v1/ego/state" in caplog.text


@pytest.mark.parametrize("key, recorded", [
    ("coopdrive/v1/scene", True),
    ("coopdrive/world/clock", True),
    ("coopdrive/v1/@step/scene", False),
    ("coopdrive/world/@clock/0/1", False),
    ("coopdrive/v1/_alive/scene", False),
])
def test_traffic_is_spooled_and_step_markers_lockstep_clocks_and_liveliness_are_not(tmp_path, key, recorded):
    assert is_recorded(key) is recorded
    spool = spool_in(tmp_path, "v1-group-0")
    spool_truth(spool, key, [0.0])
    taken, _ = merged(tmp_path)
    assert len(taken) == int(recorded)


def test_an_empty_spool_of_a_process_killed_before_it_wrote_is_merged_as_nothing(tmp_path):
    (tmp_path / f"v1-control-1{SPOOL_SUFFIX}").write_bytes(b"")
    spool_truth(spool_in(tmp_path, "v1-control-0"), "coopdrive/v1/x", [0.0])
    taken, stats = merged(tmp_path)
    assert len(taken) == 1 and (stats.spools, stats.cut_spools) == (2, [])
