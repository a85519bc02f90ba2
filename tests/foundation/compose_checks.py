"""What the compose-profile tests share: the profile's healthchecks run as compose runs them (in each service's
environment), and a teardown that kills whatever is still running."""

from __future__ import annotations

import os
import subprocess

from coopdrive.launch.compose_processes import command_of

HEALTHCHECK_TIMEOUT_S = 60


def failing_healthchecks(processes) -> list[str]:
    """"name: output" of each process whose healthcheck fails."""
    failing = []
    for process in processes:
        if process.healthcheck is None:
            continue
        result = subprocess.run(command_of(process.healthcheck), capture_output=True, text=True,
                                timeout=HEALTHCHECK_TIMEOUT_S, env={**os.environ, **process.environment})
        if result.returncode != 0:
            failing.append(f"{process.name}: {result.stdout.strip()} {result.stderr.strip()}")
    return failing


def kill_all(running: dict[str, subprocess.Popen]) -> None:
    for started in running.values():
        if started.poll() is None:
            started.kill()
            started.wait()
