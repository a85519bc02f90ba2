"""ServiceProcesses: one OS process per service, each running `coopdrive service NAME`."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

TERMINATE_GRACE_S = 1.5


@dataclass
class ServiceSpec:
    service: str
    vehicle_id: str
    config: dict

    @property
    def participant(self) -> str:
        return f"{self.vehicle_id}/{self.service}"


class ServiceProcesses:
    def __init__(self, connect_endpoint: str, clock: str = "sim", log_dir: Path | None = None):
        self._connect = connect_endpoint
        self._clock = clock
        self._config_dir = Path(tempfile.mkdtemp(prefix="coopdrive-run-"))
        self._log_dir = log_dir
        self.processes: dict[str, subprocess.Popen] = {}

    def start(self, spec: ServiceSpec) -> None:
        config_path = self._config_dir / f"{spec.vehicle_id}-{spec.service}.json"
        config_path.write_text(json.dumps(spec.config))
        command = [sys.executable, "-m", "coopdrive.cli", "service", spec.service, "--vehicle", spec.vehicle_id,
                   "--connect", self._connect, "--clock", self._clock, "--config", str(config_path)]
        output = None
        if self._log_dir is not None:
            self._log_dir.mkdir(parents=True, exist_ok=True)
            output = open(self._log_dir / f"{spec.vehicle_id}-{spec.service}.log", "wb")
        self.processes[spec.participant] = subprocess.Popen(
            command, stdin=subprocess.DEVNULL, stdout=output, stderr=subprocess.STDOUT if output else None,
            start_new_session=True)

    def exited(self) -> dict[str, int]:
        """Participants whose process has ended, with their exit codes."""
        return {name: p.returncode for name, p in self.processes.items() if p.poll() is not None}

    def kill(self, participant: str) -> None:
        """Kills one service abruptly (fault injection: a service crash)."""
        self.processes[participant].kill()

    def stop_all(self) -> None:
        for process in self.processes.values():
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + TERMINATE_GRACE_S
        for process in self.processes.values():
            try:
                process.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
