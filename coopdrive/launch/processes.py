"""ServiceProcesses: the OS processes of a run, one per service (`coopdrive service NAME`) or one per
group of services (`coopdrive group SPEC`, a vehicle's whole stack in simulation)."""

from __future__ import annotations

import json
import multiprocessing
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from coopdrive.launch.forked_process import ForkedProcess
from coopdrive.bus.publish_spool import SPOOL_PATH_ENV
from coopdrive.recording.spool_merge import SPOOL_SUFFIX, SpoolMerge
from coopdrive.runtime.launcher_watch import launcher_environment

TERMINATE_GRACE_S = 1.5
# Zenoh's runtimes default to several threads each. A run puts a process per service on a few cores, where
# each service's traffic is a handful of messages per step: one thread per runtime hands them on with fewer
# wake-ups (follow: about 8 % less CPU). A ZENOH_RUNTIME set by the user wins.
SIMULATION_ZENOH_RUNTIME = ("(rx: (worker_threads: 1), tx: (worker_threads: 1), net: (worker_threads: 1), "
                            "acc: (worker_threads: 1), app: (worker_threads: 1))")

# Set to "1", every service starts as a new interpreter instead of a fork of the preloaded server (forked_process.py):
# for a native library that misbehaves after a fork, and as bench_startup's baseline.
NEW_INTERPRETERS_VARIABLE = "COOPDRIVE_NEW_INTERPRETERS"


@dataclass
class ServiceSpec:
    service: str
    vehicle_id: str
    config: dict

    @property
    def participant(self) -> str:
        return f"{self.vehicle_id}/{self.service}"


class ServiceProcesses:
    def __init__(self, connect_endpoint: str, clock: str = "sim", log_dir: Path | None = None,
                 clock_step_s: float | None = None, spool_dir: Path | None = None,
                 spool_merge: SpoolMerge | None = None, on_started: Callable[[str, int], None] | None = None):
        """`clock_step_s`: the simulator's step, told to every service (`--clock-step`). `spool_dir`: where each
        process writes what it publishes for the run's recording (publish_spool.py), one file per process start;
        `spool_merge` is told of each spool as its process starts, and once its process has ended.
        `on_started(name, pid)`: told of each process as it starts (RunOptions.on_process_started)."""
        self._on_started = on_started
        self._connect = connect_endpoint
        self._clock = clock
        self._clock_step = [] if clock_step_s is None else ["--clock-step", repr(clock_step_s)]
        self._config_dir = Path(tempfile.mkdtemp(prefix="coopdrive-run-"))
        self._log_dir = log_dir
        # Process name ("<vehicle>/<service>" or "<vehicle>/group") -> process.
        self.processes: dict[str, ForkedProcess | subprocess.Popen] = {}
        # Participant -> the name of the process it runs in.
        self.process_of: dict[str, str] = {}
        # Process name -> what it was started with, to start it again.
        self._started_with: dict[str, tuple[list[ServiceSpec], list[str]]] = {}
        self._spool_dir = spool_dir
        self._spool_merge = spool_merge
        self._starts: dict[str, int] = {}
        # Process name -> the spool of its current start.
        self._spool_of: dict[str, Path] = {}

    def start(self, spec: ServiceSpec) -> None:
        config_path = self._config_dir / f"{spec.vehicle_id}-{spec.service}.json"
        config_path.write_text(json.dumps(spec.config))
        self._spawn(spec.participant, [spec], ["service", spec.service, "--vehicle", spec.vehicle_id,
                                               "--config", str(config_path)])

    def start_group(self, name: str, specs: list[ServiceSpec]) -> None:
        """Runs `specs` in one process named `name` (e.g. "v3/group")."""
        spec_path = self._config_dir / f"{name.replace('/', '-')}.json"
        spec_path.write_text(json.dumps([{"service": s.service, "vehicle": s.vehicle_id, "config": s.config}
                                         for s in specs]))
        self._spawn(name, specs, ["group", str(spec_path)])

    def _spawn(self, name: str, specs: list[ServiceSpec], arguments: list[str], log_mode: str = "wb") -> None:
        command = [*arguments, "--connect", self._connect, "--clock", self._clock, *self._clock_step]
        log_path = None
        if self._log_dir is not None:
            # A user who asks for the logs gets what the services tell at INFO, such as the planner's transitions.
            command.append("--verbose")
            self._log_dir.mkdir(parents=True, exist_ok=True)
            log_path = self._log_dir / f"{name.replace('/', '-')}.log"
        environment, spool = self._environment_of(name)
        if multiprocessing.current_process().daemon or os.environ.get(NEW_INTERPRETERS_VARIABLE) == "1":
            # A daemonic process (a Dask worker's, by default) may not fork children of its own: a new interpreter.
            self.processes[name] = _new_interpreter(command, environment, log_path, log_mode)
        else:
            self.processes[name] = ForkedProcess(command, environment, log_path, log_mode)
        if spool is not None:
            # Only now, with the new process in place: until then exited() (the launcher's thread) still sees the
            # old one, ended, and would tell the merge that this new spool, still empty, was whole (a restarted
            # service's messages then never reached the recording, seen when its start took long on a busy machine).
            self._spool_of[name] = spool
        self._started_with[name] = (specs, arguments)
        for spec in specs:
            self.process_of[spec.participant] = name
        if self._on_started is not None:
            self._on_started(name, self.processes[name].pid)

    @staticmethod
    def environment() -> dict[str, str]:
        """A service's environment: ours (a ZENOH_RUNTIME set by the user wins over the simulation's), and this
        process as its launcher, so that the service ends with it."""
        return {"ZENOH_RUNTIME": SIMULATION_ZENOH_RUNTIME, **os.environ, **launcher_environment()}

    def _environment_of(self, name: str) -> tuple[dict[str, str], Path | None]:
        """The environment of this start of process `name` and, with a spool directory, its spool file: named after
        the process and numbered from 0 by its starts, so that a recording's order is the same in every run."""
        environment = self.environment()
        environment.pop(SPOOL_PATH_ENV, None)
        if self._spool_dir is None:
            return environment, None
        start = self._starts[name] = self._starts.get(name, -1) + 1
        spool = self._spool_dir / f"{name.replace('/', '-')}-{start}{SPOOL_SUFFIX}"
        environment[SPOOL_PATH_ENV] = str(spool)
        if self._spool_merge is not None:
            self._spool_merge.add(spool)  # before the process can write it
        return environment, spool

    def exited(self) -> dict[str, int]:
        """Processes that have ended, with their exit codes; the merge learns that their spools are whole."""
        ended = {name: p.returncode for name, p in self.processes.items() if p.poll() is not None}
        for name in ended:
            self._spool_ended(name)
        return ended

    def _spool_ended(self, name: str) -> None:
        if self._spool_merge is not None and name in self._spool_of:
            self._spool_merge.writer_gone(self._spool_of[name])

    def kill(self, participant: str) -> None:
        """Kills the process running a service abruptly (fault injection: a service crash)."""
        self.processes[self.process_of[participant]].kill()

    def restart(self, participant: str) -> None:
        """Starts the process running a service again, as compose's `restart: on-failure` would after a crash;
        its log goes on in the same file."""
        name = self.process_of[participant]
        old = self.processes[name]
        if old.poll() is None:
            old.kill()
        old.wait()
        self._spool_ended(name)
        self._spawn(name, *self._started_with[name], log_mode="ab")

    def stop_all(self) -> None:
        for process in self.processes.values():
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + TERMINATE_GRACE_S
        for process in self.processes.values():
            try:
                process.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                try:
                    os.killpg(process.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass  # it ended between the timeout and the kill
                process.wait()
        shutil.rmtree(self._config_dir, ignore_errors=True)


def _new_interpreter(command: list[str], environment: dict[str, str], log_path: Path | None,
                     log_mode: str) -> subprocess.Popen:
    output = open(log_path, log_mode) if log_path is not None else None
    try:
        return subprocess.Popen([sys.executable, "-m", "coopdrive.cli", *command], stdin=subprocess.DEVNULL,
                                stdout=output, stderr=subprocess.STDOUT if output else None,
                                start_new_session=True, env=environment)
    finally:
        if output is not None:
            output.close()  # the child has its own descriptor
