"""A live exchange between stations, each a process on its own end of a wire (our_station.py, flexstack_peer.py
with --go-on-stdin): all are started, each says `ready` when it can exchange, then all are told to go at once and
each prints one JSON summary when its duration is over. Every process is killed at the end, whatever happened.

    summaries = run_exchange({"ours": argv_a, "peer": argv_b}, logs_dir)
"""

from __future__ import annotations

import json
import os
import select
import signal
import subprocess
import time
from pathlib import Path

from tests.v2x.live.our_station import READY
from tests.v2x.live.stations import ROOT

# How long a station may take to start (interpreter, imports, Zenoh, the service) on a machine loaded by a full
# test run; and to finish after its duration.
READY_TIMEOUT_S = 180.0
FINISH_TIMEOUT_S = 120.0


class ExchangeError(RuntimeError):
    """A station that did not get ready, or ended without its summary: names it and shows its stderr's end."""


def _tail(path: Path, lines: int = 15) -> str:
    return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])


def _wait_ready(name: str, process: subprocess.Popen, stderr: Path, deadline: float) -> None:
    while (remaining_s := deadline - time.monotonic()) > 0:
        readable, _, _ = select.select([process.stdout], [], [], remaining_s)
        if not readable:
            break
        line = process.stdout.readline()
        if line.strip() == READY:
            return
        if line == "":
            raise ExchangeError(f"station {name} ended before it was ready:\n{_tail(stderr)}")
    raise ExchangeError(f"station {name} not ready within {READY_TIMEOUT_S:.0f} s:\n{_tail(stderr)}")


def _summary(name: str, process: subprocess.Popen, stderr: Path) -> dict:
    output, _ = process.communicate(timeout=FINISH_TIMEOUT_S)
    lines = output.strip().splitlines()
    if process.returncode != 0 or not lines:
        raise ExchangeError(f"station {name} ended with status {process.returncode} and no summary:\n"
                            f"{_tail(stderr)}")
    return json.loads(lines[-1])


def run_exchange(stations: dict[str, list[str]], logs_dir: Path) -> dict[str, dict]:
    """Runs the stations' argvs together (in the repository, where `python -m tests...` finds our harness); returns
    each one's summary by name. Their stderr stays in logs_dir."""
    processes: dict[str, tuple[subprocess.Popen, Path]] = {}
    try:
        for name, argv in stations.items():
            stderr = logs_dir / f"{name}.stderr"
            with stderr.open("w") as stderr_file:
                processes[name] = (subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                                    stderr=stderr_file, text=True, start_new_session=True,
                                                    cwd=ROOT),
                                   stderr)
        deadline = time.monotonic() + READY_TIMEOUT_S
        for name, (process, stderr) in processes.items():
            _wait_ready(name, process, stderr, deadline)
        for process, _ in processes.values():
            process.stdin.write("go\n")
            process.stdin.flush()
        return {name: _summary(name, process, stderr) for name, (process, stderr) in processes.items()}
    finally:
        for process, _ in processes.values():
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
