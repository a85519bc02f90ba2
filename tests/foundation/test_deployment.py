"""Deployment files: compose validates, maps to real services, and the wheel is a normal one."""

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import yaml

from coopdrive.runtime.registry import service_class
from tests.system_packages import needs

ROOT = Path(__file__).resolve().parents[2]


def compose_services() -> dict:
    """The stack's services on the vehicle (the default profile, through .env) and the router they share."""
    services = yaml.safe_load((ROOT / "docker-compose.yml").read_text())["services"]
    return {name: spec for name, spec in services.items() if spec.get("profiles", ["vehicle"]) == ["vehicle"]}


def test_the_vehicle_profile_is_the_default_and_each_profile_has_its_router():
    assert "COMPOSE_PROFILES=vehicle" in (ROOT / ".env").read_text().splitlines()
    services = yaml.safe_load((ROOT / "docker-compose.yml").read_text())["services"]
    assert services["zenohd"]["profiles"] == ["vehicle"]
    assert {name for name, spec in services.items() if spec.get("profiles") == ["desk"]} == \
        {"desk-zenohd", "desk-sim", "desk-stack", "desk-gateway", "desk-foxglove"}


def test_on_the_vehicle_the_router_takes_only_mutual_tls_with_the_generated_rules_and_counts_its_refusals():
    router = compose_services()["zenohd"]
    command = router["command"]
    assert command[:3] == ["router", "--config", "/credentials/router/zenohd.json5"]
    assert command[command.index("--listen") + 1].endswith(":-tls/0.0.0.0:7447}") and "--count-denials" in command
    assert router["volumes"] == ["${COOPDRIVE_BUS_CREDENTIALS:-./credentials}:/credentials:ro"]


def test_on_the_vehicle_every_process_connects_with_its_own_credentials_mounted_read_only():
    for name, spec in compose_services().items():
        if name == "zenohd":
            continue
        holder = {"record": "recorder"}.get(name, name)
        own = f"/credentials/{holder}/zenoh.json5"
        assert "--connect" not in spec["command"] and spec["command"][spec["command"].index("--zenoh-config") + 1] \
            == own, name
        assert "${COOPDRIVE_BUS_CREDENTIALS:-./credentials}:/credentials:ro" in spec["volumes"], name
        assert spec["environment"]["COOPDRIVE_BUS_SECURITY"] == "mtls", name
        if "healthcheck" in spec and not spec["healthcheck"].get("disable"):
            assert own in spec["healthcheck"]["test"], name


def test_on_the_desk_the_bus_is_plain_tcp_on_loopback_only():
    services = yaml.safe_load((ROOT / "docker-compose.yml").read_text())["services"]
    assert services["desk-zenohd"]["command"][-1] == "${COOPDRIVE_ZENOH_LISTEN:-tcp/127.0.0.1:7447}"
    assert '"tcp/127.0.0.1:7447"' in (ROOT / "deploy" / "config" / "zenohd.json5").read_text()
    for name, spec in services.items():
        if spec.get("profiles") == ["desk"] and name != "desk-zenohd":
            assert "COOPDRIVE_BUS_SECURITY" not in spec["environment"], name


def test_the_bus_credentials_never_enter_the_image():
    assert "credentials/" in (ROOT / ".dockerignore").read_text().splitlines()
    copied = [line.split()[1:-1] for line in (ROOT / "Dockerfile").read_text().splitlines() if line.startswith("COPY")]
    assert not any("credentials" in source or source == "." for sources in copied for source in sources)


def test_on_the_vehicle_a_service_without_its_device_waits_for_it_instead_of_restarting():
    for name, spec in compose_services().items():
        if spec["command"][0] == "service":
            assert spec["command"][-2:] == ["--hardware-retry", "5"], name


def test_compose_records_the_bus_to_a_mounted_folder_only_when_the_record_profile_is_asked_for():
    services = yaml.safe_load((ROOT / "docker-compose.yml").read_text())["services"]
    record = services["record"]
    assert record["profiles"] == ["record"]
    assert record["command"][:2] == ["record", "/recordings/"]
    assert any(volume.endswith(":/recordings") for volume in record["volumes"])
    assert record["stop_signal"] == "SIGINT"  # the recorder finishes its file on SIGINT or SIGTERM


def test_every_compose_service_runs_a_real_coopdrive_service():
    for name, spec in compose_services().items():
        if name == "zenohd":
            assert spec["image"].startswith("coopdrive") and spec["command"][0] == "router"
            continue
        command = spec["command"]
        if name == "foxglove":
            assert command[0] == "foxglove" and "healthcheck" in spec
            continue
        assert command[:2] == ["service", name], f"{name} does not run 'coopdrive service {name}'"
        assert service_class(name).name == name
        assert spec["restart"] == "on-failure" and "healthcheck" in spec
        config = command[command.index("--config") + 1]
        assert (ROOT / "deploy" / "config" / Path(config).name).exists(), f"{name}: {config} is not in deploy/config"


def test_every_deployed_config_is_valid_for_its_service():
    for name, spec in compose_services().items():
        if name in ("zenohd", "foxglove"):
            continue
        command = spec["command"]
        config = yaml.safe_load((ROOT / "deploy" / "config" / Path(command[command.index("--config") + 1]).name)
                                .read_text()) or {}
        service_class(name).Config.model_validate(config)


def test_on_the_vehicle_actuation_owns_the_car_s_bus_scene_reads_the_radar_s_and_geolocation_its_gnss():
    def deployed(name: str) -> dict:
        return yaml.safe_load((ROOT / "deploy" / "config" / f"{name}.yaml").read_text())

    # Actuation reads the car's bus and publishes it on can/vehicle, which geolocation reads from the bus.
    assert (deployed("actuation")["can_port"]["interface"], deployed("actuation")["can_port"]["channel"]) == \
        ("socketcan", "can0")
    assert "can_port" not in deployed("geolocation")
    assert deployed("scene")["can_port"]["interface"] == "socketcan"
    gnss_port = deployed("geolocation")["gnss_port"]
    assert any(device.endswith(f":{gnss_port}") for device in compose_services()["geolocation"]["devices"])


@needs("docker-compose")
@pytest.mark.parametrize("profile", [None, "vehicle", "desk", "record"])
def test_docker_compose_accepts_the_file_with_each_profile(profile):
    chosen = [] if profile is None else ["--profile", profile]
    result = subprocess.run(["docker-compose", "-f", str(ROOT / "docker-compose.yml"), *chosen, "config", "-q"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr


def test_the_health_command_reports_a_missing_service_as_not_alive(endpoint):
    result = subprocess.run([sys.executable, "-m", "coopdrive.cli", "health", "--connect", endpoint,
                             "--service", "control", "--timeout", "0.5"], capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert "ego/control: not alive" in result.stdout


def test_pip_builds_a_normal_wheel_with_one_top_level_package(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w",
                    str(tmp_path), str(ROOT)], check=True, timeout=300, capture_output=True)
    [wheel] = tmp_path.glob("coopdrive-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    top_level = {name.split("/")[0] for name in names if not name.startswith("coopdrive-")}
    assert top_level == {"coopdrive"}
    for expected in ("coopdrive/services/control/service.py", "coopdrive/v1/ego_pb2.py", "coopdrive/cli.py"):
        assert expected in names
    entry_points = next(n for n in names if n.endswith("entry_points.txt"))
    assert "coopdrive = coopdrive.cli:entry" in zipfile.ZipFile(wheel).read(entry_points).decode()


def test_the_desk_stack_is_configured_as_a_run_of_the_follow_scenario_configures_its_stack():
    import json

    from coopdrive.launch.desk import desk_stack
    from coopdrive.services.sim.config import SimConfig

    stack = desk_stack()
    assert json.loads((ROOT / "deploy" / "desk" / "stack.json").read_text()) == stack
    for entry in stack:
        service_class(entry["service"]).Config.model_validate(entry["config"])
    geolocation = next(entry["config"] for entry in stack if entry["service"] == "geolocation")
    assert geolocation["map_name"] == "a270" and "gnss_port" not in geolocation  # fixes come on gnss/fix
    sim = SimConfig.model_validate(yaml.safe_load((ROOT / "deploy" / "desk" / "sim.yaml").read_text()))
    assert sim.participants == [entry["vehicle"] + "/" + entry["service"] for entry in stack]
    assert (sim.scenario, sim.lockstep, sim.paced) == ("follow", False, True)  # the wall clock, no barrier
