"""Acceptance of the authenticated bus (issue 75): the desk stack as processes (the desk profile's simulator, the
vehicle's five services, the gateway and the Foxglove bridge) on the credentials `coopdrive pki bus --simulated`
makes, each service a process of its own with its own certificate (a `coopdrive group` shares one session, hence one
certificate), behind a real `coopdrive router` that counts what it refuses. The car drives (ego/state's speed rises),
the gateway lists every service alive, every service's diagnostics say its session is authenticated, and the router
refused nothing."""

import json
import os
import queue
import signal
import subprocess
import time
from pathlib import Path

import httpx
import pytest

from coopdrive.bus import Bus, BusConfig
from coopdrive.launch.compose_processes import command_of
from coopdrive.launch.ports import free_tcp_port

ROOT = Path(__file__).resolve().parents[2]
VEHICLE = "ego"
OBSERVER = "laptop"
DEADLINE_S = 240.0
DRIVING_MPS = 2.0
SECURE = {**os.environ, "COOPDRIVE_BUS_SECURITY": "mtls"}


@pytest.fixture(scope="module")
def desk(tmp_path_factory):
    """Starts the secured desk; yields (credentials folder, gateway port, router log, processes)."""
    folder = tmp_path_factory.mktemp("secure-desk")
    credentials, router = folder / "credentials", f"tls/127.0.0.1:{free_tcp_port()}"
    made = subprocess.run(command_of(["pki", "bus", str(credentials), "--vehicle", VEHICLE, "--simulated",
                                      "--observer", OBSERVER, "--observer", "foxglove", "--router", router]),
                          capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    gateway_port = free_tcp_port()
    running: dict[str, subprocess.Popen] = {}
    try:
        for name, arguments in desk_commands(credentials, router, gateway_port, folder):
            with open(folder / f"{name}.log", "w") as log:
                running[name] = subprocess.Popen(command_of(arguments), env=SECURE, stdout=log,
                                                 stderr=subprocess.STDOUT, start_new_session=True)
            if name == "router":
                wait_for(lambda: "listening" in (folder / "router.log").read_text(), "the router listens")
        yield credentials, gateway_port, folder / "router.log", running
    finally:
        for process in running.values():
            if process.poll() is None:
                process.kill()
                process.wait()


def desk_commands(credentials: Path, router: str, gateway_port: int, folder: Path) -> list[tuple[str, list[str]]]:
    def own(name: str) -> list[str]:
        return ["--zenoh-config", str(credentials / name / "zenoh.json5")]

    commands = [("router", ["router", "--config", str(credentials / "router" / "zenohd.json5"), "--listen", router,
                            "--count-denials"]),
                ("sim", ["service", "sim", "--vehicle", "world", "--config", str(ROOT / "deploy/desk/sim.yaml"),
                         "--clock", "sim", *own("sim")])]
    for entry in json.loads((ROOT / "deploy/desk/stack.json").read_text()):
        config = folder / f"{entry['service']}.json"
        config.write_text(json.dumps(entry["config"]))
        commands.append((entry["service"], ["service", entry["service"], "--vehicle", entry["vehicle"], "--config",
                                            str(config), "--clock", "sim", "--clock-step", "0.02",
                                            *own(entry["service"])]))
    commands += [("gateway", ["service", "gateway", "--vehicle", VEHICLE, "--config",
                              str(ROOT / "deploy/config/gateway.yaml"), "--set", f"port={gateway_port}", "--clock",
                              "sim", *own("gateway")]),
                 ("foxglove", ["foxglove", "--port", str(free_tcp_port()), "--vehicle", VEHICLE, *own("foxglove")])]
    return commands


def wait_for(condition, what: str, deadline_s: float = DEADLINE_S):
    end = time.monotonic() + deadline_s
    while not (result := condition()):
        assert time.monotonic() < end, f"never: {what}"
        time.sleep(0.5)
    return result


def test_the_secured_desk_drives_with_every_service_authenticated_and_nothing_refused(desk):
    credentials, gateway_port, router_log, running = desk
    observer = Bus(BusConfig(zenoh_config_file=str(credentials / OBSERVER / "zenoh.json5")))
    states: queue.Queue = queue.Queue()
    reports: dict[str, str] = {}
    try:
        observer.subscribe(VEHICLE, "ego/state", states.put)
        for service in ("geolocation", "scene", "planner", "control", "actuation", "gateway"):
            observer.subscribe(VEHICLE, f"diagnostics/{service}",
                               lambda envelope: reports.__setitem__(envelope.message.header.sender,
                                                                    envelope.message.message))
        observer.subscribe("world", "diagnostics/sim",
                           lambda envelope: reports.__setitem__("sim", envelope.message.message))
        wait_for(lambda: _faster_than(states, DRIVING_MPS, running), f"ego/state faster than {DRIVING_MPS} m/s")
        wait_for(lambda: len(reports) == 7, "every service's diagnostics")
        assert set(reports.values()) == {"bus mtls"}, reports
        health = wait_for(lambda: _all_running(gateway_port), "the gateway lists every service running")
        assert health["bus_mode"] == "mtls"
    finally:
        observer.close()
    running["router"].send_signal(signal.SIGTERM)  # it reports a count not yet printed as it ends
    assert running["router"].wait(timeout=60) == 0
    assert "access control denials" not in router_log.read_text(), router_log.read_text()


def _faster_than(states: queue.Queue, speed_mps: float, running) -> bool:
    ended = [name for name, process in running.items() if process.poll() is not None]
    assert not ended, f"ended: {ended}"
    while not states.empty():
        if states.get().message.speed_mps > speed_mps:
            return True
    return False


def _all_running(port: int) -> dict | None:
    try:
        health = httpx.get(f"http://127.0.0.1:{port}/health", timeout=10).json()
    except httpx.TransportError:
        return None
    wanted = {"sim", "geolocation", "scene", "planner", "control", "actuation"}
    running = {name for name, service in health["services"].items() if service["status"] == "running"}
    return health if wanted <= running else None
