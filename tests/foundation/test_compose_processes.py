"""docker-compose.yml's desk profile run as processes, each with exactly the command, config and environment compose
would give its container (coopdrive/launch/compose_processes.py; `coopdrive router` for the zenohd image): every
healthcheck passes, the gateway's /health has every service alive, a Foxglove client gets LocationFix, and each
process ends cleanly within 3 s of SIGTERM."""

import subprocess
import time
from pathlib import Path

import httpx
import pytest
import yaml
from foxglove_schemas_protobuf.LocationFix_pb2 import LocationFix

from coopdrive.launch.compose_processes import compose_processes, interpolate, start_all, stop
from tests.foundation.compose_checks import failing_healthchecks, kill_all
from coopdrive.launch.ports import free_tcp_port, loopback_endpoint
from tests.system_packages import needs
from tests.visual.foxglove_ws_client import watch

ROOT = Path(__file__).resolve().parents[2]
STOP_BOUND_S = 3.0
# Generous: nine interpreters start on a loaded 2-core machine, and the simulator waits for its stack.
HEALTHY_TIMEOUT_S = 150.0
DESK_SERVICES = {"sim", "geolocation", "scene", "planner", "control", "actuation"}


@pytest.fixture(scope="module")
def desk_environment():
    endpoint = loopback_endpoint(free_tcp_port())
    return {"COOPDRIVE_ZENOH": endpoint, "COOPDRIVE_ZENOH_LISTEN": endpoint,
            "COOPDRIVE_GATEWAY_PORT": str(free_tcp_port()), "COOPDRIVE_FOXGLOVE_PORT": str(free_tcp_port())}


@pytest.fixture(scope="module")
def desk_logs(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("desk-logs")


@pytest.fixture(scope="module")
def desk(desk_environment, desk_logs):
    processes = compose_processes(["desk"], desk_environment)
    running = start_all(processes, desk_logs)
    yield processes, running
    kill_all(running)



def test_the_desk_profile_runs_the_simulator_one_stack_the_gateway_and_the_foxglove_bridge(desk_environment,
                                                                                          tmp_path):
    names = [process.name for process in compose_processes(["desk"], desk_environment)]
    assert names == ["desk-zenohd", "desk-sim", "desk-stack", "desk-gateway", "desk-foxglove"]
    on_the_vehicle = {**desk_environment, "COOPDRIVE_BUS_CREDENTIALS": str(tmp_path)}  # the folder must exist
    vehicle = [process.name for process in compose_processes(["vehicle"], on_the_vehicle)]
    assert "desk-sim" not in vehicle and {"geolocation", "actuation", "gateway", "foxglove"} <= set(vehicle)


def test_every_desk_process_passes_its_healthcheck_and_the_gateway_lists_every_service_alive(desk, desk_logs,
                                                                                               desk_environment):
    processes, running = desk
    deadline = time.monotonic() + HEALTHY_TIMEOUT_S
    while (failing := failing_healthchecks(processes)) and time.monotonic() < deadline:
        assert all(p.poll() is None for p in running.values()), _ended(running, desk_logs)
        time.sleep(1.0)
    assert not failing
    url = f"http://127.0.0.1:{desk_environment['COOPDRIVE_GATEWAY_PORT']}/health"
    while True:
        services = httpx.get(url, timeout=10).json()["services"]
        alive = {name for name, service in services.items() if service["alive"] and service["status"] == "running"}
        if DESK_SERVICES <= alive or time.monotonic() > deadline:
            break
        time.sleep(1.0)
    assert DESK_SERVICES <= alive, services


def test_a_foxglove_client_of_the_desk_receives_location_fixes(desk, desk_environment):
    received = watch(f"ws://127.0.0.1:{desk_environment['COOPDRIVE_FOXGLOVE_PORT']}", ["foxglove/ego/ego"],
                     HEALTHY_TIMEOUT_S, 1.0)
    channel = received.channel_by_topic("foxglove/ego/ego")
    assert channel["schemaName"] == "foxglove.LocationFix"
    fixes = [LocationFix.FromString(payload) for _, payload in received.messages["foxglove/ego/ego"]]
    assert fixes and abs(fixes[-1].latitude - 51.4758) < 0.1  # the follow world's origin


def test_sigterm_ends_every_desk_process_cleanly_within_3_s(desk, desk_logs):
    processes, running = desk
    assert all(p.poll() is None for p in running.values()), _ended(running, desk_logs)
    for process in reversed(processes):  # the router last, as compose stops dependencies after their dependents
        started = time.monotonic()
        try:
            code = stop(process, running[process.name], timeout_s=STOP_BOUND_S)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{process.name} still running {STOP_BOUND_S:g} s after SIGTERM")
        assert code == 0, f"{process.name} exited {code} after {time.monotonic() - started:.1f} s: " \
                          f"{_log(desk_logs, process.name)}"


@needs("docker-compose")
def test_docker_compose_resolves_the_desk_services_as_these_processes_are_given_them(desk_environment):
    import os

    result = subprocess.run(["docker-compose", "-f", str(ROOT / "docker-compose.yml"), "--profile", "desk", "config"],
                            capture_output=True, text=True, timeout=60, env={**os.environ, **desk_environment})
    assert result.returncode == 0, result.stderr
    resolved = yaml.safe_load(result.stdout)["services"]
    ours = interpolate(yaml.safe_load((ROOT / "docker-compose.yml").read_text()), desk_environment)["services"]
    for process in compose_processes(["desk"], desk_environment):
        theirs = resolved[process.name]
        assert theirs["command"] == ours[process.name]["command"]
        assert theirs.get("environment", {}) == process.environment
        if process.healthcheck is not None:
            assert theirs["healthcheck"]["test"] == ["CMD", "coopdrive", *ours[process.name]["healthcheck"]["test"][2:]]


@needs("docker-compose")
@pytest.mark.parametrize("profile", ["vehicle", "desk"])
def test_docker_compose_accepts_both_profiles(profile):
    result = subprocess.run(["docker-compose", "-f", str(ROOT / "docker-compose.yml"), "--profile", profile,
                             "config", "-q"], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr


def _log(folder: Path, name: str) -> str:
    return (folder / f"{name}.log").read_text(errors="replace")[-1500:]


def _ended(running, folder: Path) -> str:
    return "; ".join(f"{name} exited {p.returncode}: {_log(folder, name)}"
                     for name, p in running.items() if p.poll() is not None)
