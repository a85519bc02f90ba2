"""Instructions that replaying one service executes: the working tree against a git revision, on one recording.

    .venv/bin/python -m bench.replay_instructions --against HEAD~3
    .venv/bin/python -m bench.replay_instructions --against REV --service scene --vehicle v4 --recording RUN.mcap

A change meant to make a service cheaper is measured here when the machine's load moves CPU times by more than the
change (on this shared 2-core machine the same replay took 1.2 to 2.2 s of CPU within minutes). valgrind's
callgrind counts the instructions a process executes, which the load does not move: the same count for the same
code and inputs. Each service is replayed (`coopdrive replay`) from the same recording by both trees; its start-up
(imports, the service's start, reading the recording) is counted in a replay that stops at START_UP_WINDOW_S and
subtracted, so the table compares the stepping alone. Without --recording the working tree records a `string` run
first (--stacks, --duration). A native replay of each tree says whether its outputs are identical to the
recording's, the check that a speed change left the service's behaviour alone (under valgrind numpy may take other
SIMD kernels, so that check is made outside it).

Instructions are not time: a numpy call and a Python call of the same count differ in cache misses and branches.
They are the like-for-like figure; `make bench` and `bench.profile_handlers` give the times.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from rich.table import Table

from bench.callgrind import CallgrindError, collected, run_under_callgrind
from bench.tree_at_revision import tree_at_revision
from coopdrive.exit_status import EXIT_FAILED, EXIT_OK

START_UP_WINDOW_S = 0.1
WORKERS = 2
REPLAY_RAN = (EXIT_OK, EXIT_FAILED)


def instructions(command: list[str], env: dict[str, str] | None = None, cwd: Path | None = None,
                 ok_exit_codes: tuple[int, ...] = (EXIT_OK,)) -> int:
    """Instructions the command's process executed (callgrind's total); CallgrindError with its output's end if it
    ended with another exit code or valgrind is missing."""
    with tempfile.TemporaryDirectory(prefix="callgrind-") as folder:
        return collected(run_under_callgrind(command, Path(folder) / "callgrind.out", env=env, cwd=cwd,
                                             ok_exit_codes=ok_exit_codes))


@dataclass(frozen=True)
class Replay:
    tree: Path
    recording: Path
    service: str
    vehicle: str

    def command(self, to_s: float | None = None, as_json: bool = False) -> list[str]:
        command = [sys.executable, "-m", "coopdrive.cli", "replay", str(self.recording), "--service", self.service,
                   "--vehicle", self.vehicle]
        return command + (["--to", str(to_s)] if to_s is not None else []) + (["--json"] if as_json else [])

    def env(self) -> dict[str, str]:
        return {**os.environ, "PYTHONPATH": str(self.tree)}

    def identical(self) -> bool:
        """Whether the replay, run natively, gives exactly the recorded outputs."""
        result = subprocess.run(self.command(as_json=True), capture_output=True, text=True, env=self.env(),
                                cwd=self.tree)
        if not result.stdout.strip():
            raise CallgrindError(f"replay of {self.service} in {self.tree} failed: {result.stderr[-1500:]}")
        return bool(json.loads(result.stdout)["identical"])

    def stepping_instructions(self, pool: ThreadPoolExecutor) -> int:
        # In its own tree: `python -m` puts the working directory first on the path, before PYTHONPATH.
        # A replay whose outputs moved (numpy's other kernels under valgrind) ends with EXIT_FAILED, and still counts.
        whole = pool.submit(instructions, self.command(), self.env(), self.tree, REPLAY_RAN)
        start_up = pool.submit(instructions, self.command(START_UP_WINDOW_S), self.env(), self.tree, REPLAY_RAN)
        return whole.result() - start_up.result()


def record_string_run(folder: Path, stacks: int, duration_s: float) -> Path:
    from coopdrive.launch.run import RunOptions, run_scenario

    recording = folder / "run.mcap"
    run_scenario(RunOptions(scenario="string", stacks=stacks, duration_s=duration_s, record=recording))
    return recording


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--against", required=True, help="the git revision to compare the working tree with")
    parser.add_argument("--service", action="append", help="a service to replay (default: scene and geolocation)")
    parser.add_argument("--vehicle", default="v4")
    parser.add_argument("--recording", type=Path, help="a lockstep run's recording (default: record a string run)")
    parser.add_argument("--stacks", type=int, default=8)
    parser.add_argument("--duration", type=float, default=6.0)
    args = parser.parse_args(argv)
    services = args.service or ["scene", "geolocation"]
    working_tree = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory(prefix="replay-instructions-") as folder:
        recording = args.recording or record_string_run(Path(folder), args.stacks, args.duration)
        old_tree = tree_at_revision(args.against, Path(folder) / "tree", working_tree)
        table = Table(title=f"instructions of each replay's stepping (less a replay of its first {START_UP_WINDOW_S} s),"
                            f" {recording.name}, vehicle {args.vehicle}: the working tree against {args.against}")
        for column in ("service", f"{args.against} G", "working tree G", "ratio", "identical to the recording"):
            table.add_column(column, justify="right")
        with ThreadPoolExecutor(WORKERS) as pool:
            for service in services:
                old, new = (Replay(tree, recording, service, args.vehicle) for tree in (old_tree, working_tree))
                old_count, new_count = old.stepping_instructions(pool), new.stepping_instructions(pool)
                same = f"{'yes' if old.identical() else 'NO'} / {'yes' if new.identical() else 'NO'}"
                row = (service, f"{old_count / 1e9:.3f}", f"{new_count / 1e9:.3f}", f"{new_count / old_count:.3f}",
                       same)
                print(" ".join(row), flush=True)  # each service as it is done: the whole table takes minutes
                table.add_row(*row)
        Console().print(table)


if __name__ == "__main__":
    main()
