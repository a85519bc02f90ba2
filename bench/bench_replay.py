"""Replaying one service of one vehicle from a multi-stack recording: reading only the channels that concern it
against reading every channel, and reading them through the file's message indexes against mcap's reader, turn
about, on the same recording.

A team debugging a vehicle replays its scene (or any service) out of a run of eight stacks. `coopdrive replay`
reads the channels that can hold the service's inputs, the clock and the vehicle's own outputs (the others are
neither decoded nor put in time order); "every channel" is the same replay with that choice switched off, as
every replay read before. It reads them through the MCAP file's message indexes, parsing only their records
(coopdrive/recording/channel_reader.py); "mcap's reader" is the same replay reading them as mcap's own reader does,
every record of every chunk parsed and the others dropped, as replays read before. All compare the outputs as the
command does. Each is timed on this process's CPU clock (a replay runs in it), the three taking turns, and the least
of ROUNDS turns is kept (bench/turn_about.py): a control replay takes a fraction of a second, where the medians of
wall times two runs apart differed by 23 %. BENCH_REPLAY_STACKS and BENCH_REPLAY_DURATION_S set the recorded run
(default 8 stacks, 10 simulated s).
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path
from unittest import mock

from rich.console import Console
from rich.table import Table

from bench.failure import require_success
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_about import turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.launch.run import RunOptions, run_scenario
from coopdrive.recording import reader, replay
from coopdrive.recording.replay_diff import compare_outputs

SCENARIO = "string"
STACKS = int(os.environ.get("BENCH_REPLAY_STACKS", sized(8, 2)))
DURATION_S = float(os.environ.get("BENCH_REPLAY_DURATION_S", sized(10.0, 1.0)))
SERVICES = ("scene", "control")
VEHICLE = "v1"
ROUNDS = sized(5, 1)


# How each variant reads: (every channel, through mcap's reader).
EVERY_CHANNEL, MCAP_READER, NOW = (True, True), (False, True), (False, False)


def replay_s(recording: Path, service: str, every_channel: bool, mcap_reader: bool) -> float:
    """CPU seconds of one replay and its comparison, as `coopdrive replay` makes them."""
    started_s = time.process_time()
    with mock.patch.object(replay, "_may_concern", (lambda *_: True) if every_channel else replay._may_concern), \
            mock.patch.object(reader, "indexes_every_chunk",
                              (lambda _: False) if mcap_reader else reader.indexes_every_chunk):
        result = replay.replay_service(recording, service, VEHICLE)
    compare_outputs(result.outputs, result.recorded_outputs)
    if result.mismatches():
        raise RuntimeError(f"{service} replayed unlike its recording: {result.mismatches()[:2]}")
    return time.process_time() - started_s


def main() -> list[Figure]:
    with tempfile.TemporaryDirectory(prefix="bench-replay-") as folder:
        recording = Path(folder) / "run.mcap"
        require_success(run_scenario(RunOptions(scenario=SCENARIO, stacks=STACKS, duration_s=DURATION_S,
                                                record=recording)), "the recorded run")
        size_mb = recording.stat().st_size / 1e6
        table = Table(title=f"replay of {VEHICLE}'s service from {SCENARIO} --stacks {STACKS} --duration "
                            f"{DURATION_S:g} ({size_mb:.1f} MB), least CPU of {ROUNDS} turns about")
        for column in ("service", "every channel s", "its channels, mcap's reader s", "its channels, indexes s",
                       "indexes / mcap's reader", "indexes / every channel"):
            table.add_column(column, justify="right")
        figures = []
        for service in SERVICES:
            every_turns, mcap_turns, now_turns = turns(
                [lambda variant=variant: replay_s(recording, service, *variant)
                 for variant in (EVERY_CHANNEL, MCAP_READER, NOW)], ROUNDS)
            every_s, mcap_s, now_s = min(every_turns), min(mcap_turns), min(now_turns)
            table.add_row(service, f"{every_s:.2f}", f"{mcap_s:.2f}", f"{now_s:.2f}", f"{now_s / mcap_s:.2f}",
                          f"{now_s / every_s:.2f}")
            figures += [Figure(f"{service}: every channel", every_s, Unit.S),
                        Figure(f"{service}: its channels, mcap's reader", mcap_s, Unit.S),
                        Figure(f"{service}: its channels, indexes", now_s, Unit.S),
                        ratio(f"{service}: indexes to mcap's reader", now_s / mcap_s,
                              f"{service}: its channels, mcap's reader", Better.LOWER,
                              spread=turn_ratio_spread(now_turns, mcap_turns)),
                        ratio(f"{service}: indexes to every channel", now_s / every_s, f"{service}: every channel",
                              Better.LOWER, spread=turn_ratio_spread(now_turns, every_turns))]
        Console(highlight=False).print(table)
    return figures


if __name__ == "__main__":
    main()
