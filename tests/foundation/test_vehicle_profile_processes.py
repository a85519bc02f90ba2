"""docker-compose.yml's vehicle profile run as processes (coopdrive/launch/compose_processes.py) on the credentials
`coopdrive pki bus` makes: the router on mutual TLS, the services that need no car (planner, control) and the Foxglove
bridge pass their healthchecks with their own certificates; the recorder of the record profile, an observer, records
their configs and no key; a service without credentials refuses to start in one line."""

import os
import queue
import subprocess
import sys
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.compose_processes import command_of, compose_processes, start_all
from coopdrive.launch.ports import free_tcp_port
from tests.foundation.compose_checks import failing_healthchecks, kill_all

VEHICLE = "car7"
WITHOUT_CAR = ("zenohd", "planner", "control", "foxglove")
HEALTHY_TIMEOUT_S = 120.0
RECORD_S = 3.0


@pytest.fixture(scope="module")
def credentials(tmp_path_factory) -> tuple[Path, str]:
    """The folder the command made for the vehicle's processes, with its observers, and the router's endpoint."""
    folder = tmp_path_factory.mktemp("vehicle") / "credentials"
    router = f"tls/127.0.0.1:{free_tcp_port()}"
    made = subprocess.run([sys.executable, "-m", "coopdrive.cli", "pki", "bus", str(folder), "--vehicle", VEHICLE,
                           "--observer", "foxglove", "--observer", "recorder", "--router", router],
                          capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    return folder, router


def vehicle_environment(folder: Path, router: str, recordings: Path | None = None) -> dict[str, str]:
    return {"COOPDRIVE_VEHICLE": VEHICLE, "COOPDRIVE_BUS_CREDENTIALS": str(folder), "COOPDRIVE_ZENOH_LISTEN": router,
            "COOPDRIVE_FOXGLOVE_PORT": str(free_tcp_port()), "COOPDRIVE_RECORDINGS": str(recordings or folder)}


@pytest.fixture(scope="module")
def vehicle(credentials, tmp_path_factory):
    folder, router = credentials
    logs = tmp_path_factory.mktemp("vehicle-logs")
    processes = [p for p in compose_processes(["vehicle"], vehicle_environment(folder, router))
                 if p.name in WITHOUT_CAR]
    running = start_all(processes, logs)
    yield processes, running, logs
    kill_all(running)



def wait_healthy(vehicle) -> None:
    processes, running, logs = vehicle
    deadline = time.monotonic() + HEALTHY_TIMEOUT_S
    while failing := failing_healthchecks(processes):
        ended = {name: (logs / f"{name}.log").read_text() for name, p in running.items() if p.poll() is not None}
        assert not ended, ended
        assert time.monotonic() < deadline, failing
        time.sleep(1.0)


def test_on_the_vehicle_profile_the_router_services_and_bridge_pass_their_healthchecks_and_nothing_is_refused(
        vehicle, credentials):
    wait_healthy(vehicle)
    folder, _ = credentials
    observer = Bus(BusConfig(zenoh_config_file=str(folder / "recorder" / "zenoh.json5")))
    reports: queue.Queue = queue.Queue()
    try:
        observer.subscribe(VEHICLE, "diagnostics/planner", reports.put)
        assert reports.get(timeout=60).message.message == "bus mtls"
    finally:
        observer.close()
    _, _, logs = vehicle
    assert "access control denials" not in (logs / "zenohd.log").read_text()  # what the stack does, it may


def test_the_recorder_of_the_record_profile_records_the_services_configs_and_no_key_nor_credentials_path(
        vehicle, credentials, tmp_path):
    wait_healthy(vehicle)
    folder, router = credentials
    [record] = [p for p in compose_processes(["record"], vehicle_environment(folder, router, tmp_path))
                if p.name == "record"]
    result = subprocess.run(command_of([*record.arguments, "--duration", str(RECORD_S)]), capture_output=True,
                            text=True, timeout=120, env={**os.environ, **record.environment})
    assert result.returncode == 0, result.stderr
    [recording] = tmp_path.glob("drive-*.mcap")
    with open(recording, "rb") as stream:
        configs = {participant: config for record in make_reader(stream).iter_metadata()
                   if record.name == "coopdrive.config" for participant, config in record.metadata.items()}
    assert {f"{VEHICLE}/planner", f"{VEHICLE}/control"} <= set(configs)
    written = recording.read_bytes()
    assert b"PRIVATE KEY" not in written and str(folder).encode() not in written and b"key.pem" not in written


def test_a_vehicle_service_without_credentials_refuses_to_start_in_one_line_saying_how_to_make_them(tmp_path):
    empty = tmp_path / "credentials"
    empty.mkdir()
    [planner] = [p for p in compose_processes(["vehicle"], vehicle_environment(empty, "tls/127.0.0.1:7447"))
                 if p.name == "planner"]
    result = subprocess.run(command_of(planner.arguments), capture_output=True, text=True, timeout=120,
                            env={**os.environ, **planner.environment})
    assert result.returncode == 2
    assert result.stderr.strip() == (f"coopdrive: no bus config {empty}/planner/zenoh.json5: make the vehicle's bus "
                                     "credentials with `coopdrive pki bus DIR --vehicle ID`")


def test_a_vehicle_service_told_to_connect_over_plain_tcp_refuses_in_one_line(tmp_path):
    result = subprocess.run(command_of(["service", "planner", "--connect", f"tcp/127.0.0.1:{free_tcp_port()}"]),
                            capture_output=True, text=True, timeout=120,
                            env={**os.environ, "COOPDRIVE_BUS_SECURITY": "mtls"})
    assert result.returncode == 2
    [line] = result.stderr.strip().splitlines()
    assert line.endswith("has no credentials (--zenoh-config): make the vehicle's bus credentials with "
                         "`coopdrive pki bus DIR --vehicle ID`")
