"""ForkedProcess: a run's service process forked from a server that has imported the services' modules once
(multiprocessing's forkserver, preloaded), instead of a new interpreter that imports them all again.

Each stack process spent 0.7-0.8 s of CPU importing the same modules (numpy, scipy, protobuf, asn1tools, cantools
and the services), so an 8-stack run spent about 7 s on it, on two cores while the others started too. The server
imports them once per launcher (a sweep's worker keeps it from run to run); a fork then starts the service as
`coopdrive group` or `coopdrive service` would, in a session of its own, with its own environment and log.

The server never opens a Zenoh session or starts a thread of ours, so a fork holds no lock and no socket it would
share with its siblings (../shared/notes/zenoh.md: a session does not survive a fork).
"""

from __future__ import annotations

import multiprocessing
import os
import subprocess
import sys
import types
from contextlib import contextmanager
from pathlib import Path

from setproctitle import setproctitle

from coopdrive.bus.services import SERVICES
from coopdrive.launch.run_aborted import RunAborted

# What every forked service needs besides its service's own module: the command line and the group runtime.
FRAMEWORK_MODULES = ("coopdrive.cli_service", "coopdrive.runtime.group", "coopdrive.runtime.runner")


def preloaded_modules() -> list[str]:
    """The simulator's and the vehicle stack's modules (the gateway, started only with --gateway, is left out)."""
    services = [entry.implementation.split(":")[0] for entry in SERVICES
                if entry.in_vehicle_stack or entry.name == "sim"]
    return [*FRAMEWORK_MODULES, *services]


def _forkserver():
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(preloaded_modules())
    return context


class ForkedProcess:
    """What ServiceProcesses uses of subprocess.Popen, for a forked service: args, pid, poll, wait, kill,
    send_signal."""

    def __init__(self, arguments: list[str], environment: dict[str, str], log_path: Path | None, log_mode: str):
        self.args = arguments
        self._process = _forkserver().Process(target=run_command, args=(arguments, environment, log_path, log_mode),
                                              name=" ".join(arguments[:2]))
        try:
            with _launchers_main_left_out():
                self._process.start()
        except (EOFError, ConnectionError) as error:
            raise RunAborted(f"the server that forks the services failed ({error}): the traceback above says which "
                             "module did not import") from None
        self.pid = self._process.pid

    @property
    def returncode(self) -> int | None:
        return self._process.exitcode

    def poll(self) -> int | None:
        return self._process.exitcode

    def wait(self, timeout: float | None = None) -> int:
        self._process.join(timeout)
        if self._process.exitcode is None:
            raise subprocess.TimeoutExpired(self.args, timeout)
        return self._process.exitcode

    def send_signal(self, signum: int) -> None:
        """Nothing once the process has ended, as Popen.send_signal: the fork server, its parent, reaps it, and
        tells us its exit code only a moment later, so a process that ends between the check and the signal is
        gone (seen: a simulator that gave up at its start timeout, stopped as it ended)."""
        if self._process.exitcode is None:
            try:
                os.kill(self.pid, signum)
            except ProcessLookupError:
                pass

    def kill(self) -> None:
        self._process.kill()


@contextmanager
def _launchers_main_left_out():
    """While a fork is asked for, __main__ is a module without a file: multiprocessing would otherwise import the
    launcher's main script again in the service (as `__mp_main__`), which costs its imports, starts the run again
    in every service if the script has no `if __name__ == "__main__":` guard, and fails if it came from stdin."""
    launchers_main = sys.modules["__main__"]
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        yield
    finally:
        sys.modules["__main__"] = launchers_main


def run_command(arguments: list[str], environment: dict[str, str], log_path: Path | None, log_mode: str) -> None:
    """In the forked process: what a new `python -m coopdrive.cli ARGUMENTS` would be, started in a session of its
    own with `environment` and its output in `log_path`."""
    os.setsid()
    setproctitle(" ".join(["coopdrive", *arguments]))  # else ps shows every service as the fork server
    os.environ.clear()
    os.environ.update(environment)
    _redirect_output(log_path, log_mode)
    from coopdrive.cli_service import main  # preloaded in the server; at module level it would load it into the launcher

    sys.exit(main(arguments))


def _redirect_output(log_path: Path | None, log_mode: str) -> None:
    stdin = os.open(os.devnull, os.O_RDONLY)
    os.dup2(stdin, 0)
    os.close(stdin)
    if log_path is None:
        return
    flags = os.O_WRONLY | os.O_CREAT | (os.O_APPEND if log_mode.startswith("a") else os.O_TRUNC)
    log = os.open(log_path, flags, 0o644)
    os.dup2(log, 1)
    os.dup2(log, 2)
    os.close(log)
