"""`coopdrive ARGS...` as a user types it: a new interpreter, its output captured, within a time limit."""

import subprocess
import sys

COMMAND_TIMEOUT_S = 300


def coopdrive(*args: str, timeout_s: float = COMMAND_TIMEOUT_S) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True,
                          timeout=timeout_s)
