"""valgrind's callgrind, run on a command: the instructions its process executes, which the machine's load does not
move (the same count for the same code and inputs), where CPU times on this shared 2-core machine move by a third
within minutes. Python's string hashes are fixed (PYTHONHASHSEED=0) so that dict and set layouts, and with them the
count, repeat from run to run."""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

from coopdrive.exit_status import EXIT_OK

# callgrind's line with the instructions of a whole run.
_COLLECTED = re.compile(r"Collected : (\d+)")
_VALGRIND_LINE = re.compile(r"==\d+==")
# The total of one profile dump (callgrind's output format: "totals: N" or, in older versions, "summary: N").
_TOTALS = re.compile(r"^(?:totals|summary): (\d+)", re.MULTILINE)


class CallgrindError(RuntimeError):
    pass


def fixed_hashes(env: dict[str, str] | None = None) -> dict[str, str]:
    return {**(os.environ if env is None else env), "PYTHONHASHSEED": "0"}


def run_under_callgrind(command: list[str], out_file: Path, options: tuple[str, ...] = (),
                        env: dict[str, str] | None = None, cwd: Path | None = None,
                        ok_exit_codes: tuple[int, ...] = (EXIT_OK,)) -> subprocess.CompletedProcess:
    """The command run by callgrind writing its profile to out_file (each further dump to out_file.N); a
    CallgrindError with the end of its output if it ended with another exit code or valgrind is missing."""
    valgrind = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}", *options]
    try:
        result = subprocess.run(valgrind + command, capture_output=True, text=True, env=env, cwd=cwd)
    except FileNotFoundError:
        raise CallgrindError("valgrind is not installed (Debian's package valgrind)") from None
    if result.returncode not in ok_exit_codes or _COLLECTED.search(result.stderr) is None:
        raise CallgrindError(f"{' '.join(command)} failed under callgrind (exit {result.returncode}): "
                             f"{last_own_line(result.stderr)}")
    return result


def last_own_line(stderr: str) -> str:
    """The command's own last line of error output (valgrind's lines start with ==PID==): the exception a Python
    traceback ends with."""
    own = [line for line in stderr.splitlines() if line.strip() and not _VALGRIND_LINE.match(line)]
    return own[-1] if own else "no output of its own"


def collected(result: subprocess.CompletedProcess) -> int:
    """A whole run's instructions, from callgrind's report."""
    return int(_COLLECTED.search(result.stderr).group(1))


def dump_total(dump: Path) -> int:
    found = _TOTALS.search(dump.read_text())
    if found is None:
        raise CallgrindError(f"{dump} holds no totals line: not a callgrind profile")
    return int(found.group(1))
