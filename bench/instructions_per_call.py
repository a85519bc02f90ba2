"""Instructions per call of each workload a benchmark names, counted by callgrind in one process.

A ratio between two code paths measured in CPU time moves with the shared machine's load: two quiet `make bench`
runs of one commit moved such ratios by up to a third (docs/performance.md). The instructions a call executes do not
move, so a benchmark whose ratio compares two pure-Python paths also counts them here and guards the ratio with
that count (bench/figure.py, `guarded_by`).

A benchmark module names its workloads with a function that returns them (the same, seeded, in every process):

    def instruction_workloads() -> list[Workload]: ...

`per_call(module_and_function)` runs `python -m bench.instructions_per_call MODULE:FUNCTION` under callgrind. The
child runs each workload's calls once to warm them (caches, the interpreter's specialised instructions), calls
os.getppid(), runs them again and calls os.getppid() again: callgrind, told to dump its counters before every call
of libc's getppid, writes each stretch between two calls to a file of its own, so a workload's counted pass is read
alone, without the start-up, the imports or the warm-up. Instructions are not time (a numpy call and a Python loop
of the same count differ in cache misses); they are the like-for-like figure where time is too noisy.
"""

from __future__ import annotations

import importlib
import json
import os
import sys
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from bench.callgrind import (
    CallgrindError,
    dump_total,
    fixed_hashes,
    run_under_callgrind,
)
from bench.sizes import sized

REPO = Path(__file__).resolve().parents[1]
MARKER_FUNCTION = "getppid"
# Dumps per workload: its warm-up pass (with everything before it), then its counted pass.
DUMPS_PER_WORKLOAD = 2


@dataclass(frozen=True)
class Workload:
    """`warm`: run the calls once before the counted pass. A workload of one long call (seconds of a Python loop)
    may leave it out: what a first call pays beyond the next (caches, specialising) is lost in its count, and
    callgrind would run it twice."""
    name: str
    calls: Sequence[Callable[[], object]]
    warm: bool = True


def run_calls(calls: Sequence[Callable[[], object]]) -> None:
    for call in calls:
        call()


def run_marked(workloads: list[Workload]) -> dict[str, int]:
    """In the child: each workload warmed, then counted between two markers; its number of calls by name."""
    for workload in workloads:
        if workload.warm:
            run_calls(workload.calls)
        os.getppid()
        run_calls(workload.calls)
        os.getppid()
    return {workload.name: len(workload.calls) for workload in workloads}


def counted_passes(out_file: Path, workloads: int) -> list[int]:
    """The counted pass of each workload: dumps 2, 4, ... (callgrind numbers a run's dumps from 1)."""
    dumps = [out_file.with_name(f"{out_file.name}.{number}") for number in range(1, DUMPS_PER_WORKLOAD * workloads + 1)]
    missing = [dump.name for dump in dumps if not dump.exists()]
    if missing:
        raise CallgrindError(f"callgrind wrote no dump {', '.join(missing)}: was os.getppid() not {MARKER_FUNCTION}?")
    return [dump_total(dump) for dump in dumps[DUMPS_PER_WORKLOAD - 1::DUMPS_PER_WORKLOAD]]


def per_call(module_and_function: str) -> dict[str, float] | None:
    """Each workload's instructions per call, by name, in the order the function returns them. At the quick size
    (the smoke test's) the workloads only run, natively in this process, and nothing is counted: callgrind's
    start-up alone takes half a minute there (tests/foundation/test_instructions_per_call.py counts)."""
    if not sized(True, False):
        run_marked(workloads_of(module_and_function))
        return None
    command = [sys.executable, "-m", "bench.instructions_per_call", module_and_function]
    with tempfile.TemporaryDirectory(prefix="instructions-per-call-") as folder:
        out_file = Path(folder) / "callgrind.out"
        # From the repository's root, as `python -m bench` runs: the child imports the workloads' module by name.
        result = run_under_callgrind(command, out_file, (f"--dump-before={MARKER_FUNCTION}",), fixed_hashes(),
                                     cwd=REPO)
        calls_by_name = json.loads(result.stdout.strip().splitlines()[-1])
        totals = counted_passes(out_file, len(calls_by_name))
    return {name: total / calls for (name, calls), total in zip(calls_by_name.items(), totals)}


def workloads_of(module_and_function: str) -> list[Workload]:
    module_name, _, function_name = module_and_function.partition(":")
    return getattr(importlib.import_module(module_name), function_name)()


if __name__ == "__main__":
    print(json.dumps(run_marked(workloads_of(sys.argv[1]))))
