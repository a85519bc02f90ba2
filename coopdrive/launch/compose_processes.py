"""A compose profile's services as local processes, each with exactly the command, config and environment compose
would give its container: the image's entrypoint (`coopdrive`) is this Python's `-m coopdrive.cli`, a mounted
folder is its place in the work tree (or the host folder a variable names), and the zenohd image is `coopdrive router` with zenohd's arguments.

`make desk` runs the desk profile this way without Docker (`python -m coopdrive.launch.compose_processes`);
tests/foundation/test_compose_processes.py runs it and checks every healthcheck, the gateway's /health, the
Foxglove bridge and a clean SIGTERM of each process.
"""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from coopdrive.exit_status import EXIT_FAILED, EXIT_OK

COMPOSE_FILE = Path(__file__).resolve().parents[2] / "docker-compose.yml"
ZENOH_IMAGE = "eclipse/zenoh"
COOPDRIVE_IMAGE = "coopdrive"
# ${VAR}, ${VAR:-default} (default when unset or empty), ${VAR-default} (when unset), and $$ for a literal $.
_VARIABLE = re.compile(r"\$\$|\$\{([A-Za-z_][A-Za-z0-9_]*)(?:(:?-)([^}]*))?\}")
ROUTER_READY_TIMEOUT_S = 60.0


class ComposeError(ValueError):
    """The compose file asks for something a local process cannot be (another image, a missing mount)."""


@dataclass(frozen=True)
class ComposeProcess:
    name: str
    arguments: list[str]  # after the `coopdrive` entrypoint
    environment: dict[str, str]
    healthcheck: list[str] | None  # `coopdrive` arguments of its healthcheck (None: it has none)
    stop_signal: str = "SIGTERM"

    @property
    def is_router(self) -> bool:
        return self.arguments[:1] == ["router"]


def interpolate(value: Any, environment: Mapping[str, str]) -> Any:
    """Compose's variable substitution in every string of a loaded compose file."""
    if isinstance(value, str):
        return _VARIABLE.sub(lambda match: _substitute(match, environment), value)
    if isinstance(value, list):
        return [interpolate(item, environment) for item in value]
    if isinstance(value, dict):
        return {key: interpolate(item, environment) for key, item in value.items()}
    return value


def _substitute(match: re.Match, environment: Mapping[str, str]) -> str:
    if match.group(0) == "$$":
        return "$"
    name, operator, default = match.groups()
    value = environment.get(name)
    if operator == ":-" and not value:
        return default
    if operator == "-" and value is None:
        return default
    return value or ""


def compose_processes(profiles: list[str], environment: Mapping[str, str],
                      compose_file: Path = COMPOSE_FILE) -> list[ComposeProcess]:
    """The services compose starts for these profiles (plus those in no profile), the router first."""
    data = interpolate(yaml.safe_load(compose_file.read_text()), environment)
    processes = []
    for name, spec in data["services"].items():
        if spec.get("profiles") and not set(spec["profiles"]) & set(profiles):
            continue
        mounts = _mounts(name, spec.get("volumes", []), compose_file.parent)
        image = spec.get("image", "")
        if image.startswith(ZENOH_IMAGE):
            arguments = ["router", *spec.get("command", [])]
        elif image.startswith(COOPDRIVE_IMAGE):
            arguments = list(spec["command"])
        else:
            raise ComposeError(f"{name}: image {image!r} is neither coopdrive's nor zenohd's")
        processes.append(ComposeProcess(name, [_on_host(a, mounts) for a in arguments],
                                        _environment(spec.get("environment")),
                                        _healthcheck(name, spec.get("healthcheck"), mounts),
                                        spec.get("stop_signal", "SIGTERM")))
    return sorted(processes, key=lambda process: not process.is_router)


def _mounts(name: str, volumes: list[str], root: Path) -> dict[str, Path]:
    """Container path -> host folder, for the bind mounts of the work tree and of absolute host folders (the bus
    credentials a test made)."""
    mounts = {}
    for volume in volumes:
        host, _, rest = volume.partition(":")
        container = rest.split(":")[0]
        if host.startswith((".", "/")):
            path = (root / host).resolve()
            if not path.exists():
                raise ComposeError(f"{name}: mounts {host}, which is not in {root}")
            mounts[container] = path
    return mounts


def _on_host(argument: str, mounts: dict[str, Path]) -> str:
    for container, host in mounts.items():
        if argument == container or argument.startswith(container.rstrip("/") + "/"):
            return str(host / argument[len(container):].lstrip("/"))
    return argument


def _environment(environment: dict | list | None) -> dict[str, str]:
    if isinstance(environment, list):
        return dict(item.split("=", 1) for item in environment)
    return {key: str(value) for key, value in (environment or {}).items()}


def _healthcheck(name: str, healthcheck: dict | None, mounts: dict[str, Path]) -> list[str] | None:
    if not healthcheck or healthcheck.get("disable"):
        return None
    test = healthcheck["test"]
    if test[:2] != ["CMD", "coopdrive"]:
        raise ComposeError(f"{name}: healthcheck {test} is not a coopdrive command")
    return [_on_host(argument, mounts) for argument in test[2:]]


def command_of(arguments: list[str]) -> list[str]:
    return [sys.executable, "-m", "coopdrive.cli", *arguments]


def start(process: ComposeProcess, log_dir: Path | None = None) -> subprocess.Popen:
    """Starts it in its own session (its stdout and stderr to log_dir/<name>.log, else piped)."""
    output = open(log_dir / f"{process.name}.log", "wb") if log_dir is not None else subprocess.PIPE
    return subprocess.Popen(command_of(process.arguments), env={**os.environ, **process.environment},
                            stdin=subprocess.DEVNULL, stdout=output,
                            stderr=subprocess.STDOUT if log_dir is not None else subprocess.PIPE,
                            start_new_session=True)


def stop(process: ComposeProcess, running: subprocess.Popen, timeout_s: float) -> int:
    """Its stop signal, then its exit code (raises subprocess.TimeoutExpired if it takes longer than timeout_s)."""
    if running.poll() is None:
        running.send_signal(getattr(signal, process.stop_signal))
    return running.wait(timeout=timeout_s)


def start_all(processes: list[ComposeProcess], log_dir: Path | None = None) -> dict[str, subprocess.Popen]:
    """The router first and, once it accepts connections (compose's depends_on), every other service."""
    running = {}
    for process in processes:
        running[process.name] = start(process, log_dir)
        if process.is_router:
            _wait_for_listener(process, running[process.name])
    return running


def _wait_for_listener(process: ComposeProcess, running: subprocess.Popen) -> None:
    endpoint = process.arguments[process.arguments.index("--listen") + 1]
    host, _, port = endpoint.split("/", 1)[1].rpartition(":")
    host = "127.0.0.1" if host in ("0.0.0.0", "[::]") else host
    deadline = time.monotonic() + ROUTER_READY_TIMEOUT_S
    while time.monotonic() < deadline and running.poll() is None:
        try:
            socket.create_connection((host, int(port)), timeout=1.0).close()
            return
        except OSError:
            time.sleep(0.2)
    raise ComposeError(f"{process.name}: nothing listens on {endpoint} after {ROUTER_READY_TIMEOUT_S:g} s")


def main(argv: list[str] | None = None) -> int:
    """`make desk`: the desk profile as processes until Ctrl-C, each one's output in out/desk/<name>.log."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m coopdrive.launch.compose_processes",
                                     description="run a docker-compose profile's services as local processes")
    parser.add_argument("--profile", action="append", default=[], help="compose profile (default: desk)")
    parser.add_argument("--logs", type=Path, default=Path("out/desk"), help="folder for each service's log")
    args = parser.parse_args(argv)
    processes = compose_processes(args.profile or ["desk"], os.environ)
    args.logs.mkdir(parents=True, exist_ok=True)
    stopping = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stopping.set())
    running = start_all(processes, args.logs)
    print(f"running {', '.join(running)}; logs in {args.logs}/; Ctrl-C stops them", flush=True)
    for process in processes:
        print(f"  {process.name}: coopdrive {' '.join(process.arguments)}", flush=True)
    while not stopping.wait(0.5) and all(p.poll() is None for p in running.values()):
        pass
    for process in reversed(processes):  # the router last
        try:
            stop(process, running[process.name], timeout_s=10.0)
        except subprocess.TimeoutExpired:
            running[process.name].kill()
    ended = {name: p.returncode for name, p in running.items() if p.returncode}
    if ended and not stopping.is_set():
        print(f"stopped because these ended: {ended} (see their logs)", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
