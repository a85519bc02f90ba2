"""`coopdrive pki bus DIR --vehicle ID` as a user runs it: the folder it writes, and one line for what it refuses."""

import datetime
import json
import stat
import subprocess
import sys

import pytest
import zenoh
from cryptography import x509
from cryptography.x509.oid import NameOID

SERVICES = ["geolocation", "v2x", "scene", "planner", "control", "actuation", "gateway"]


def coopdrive(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=120)


def certificate(path) -> x509.Certificate:
    return x509.load_pem_x509_certificate(path.read_bytes())


def common_name(path) -> str:
    return certificate(path).subject.get_attributes_for_oid(NameOID.COMMON_NAME)[0].value


def config(path) -> dict:
    return json.loads("\n".join(line for line in path.read_text().splitlines() if not line.startswith("//")))


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    directory = tmp_path_factory.mktemp("pki") / "bus"
    result = coopdrive("pki", "bus", str(directory), "--vehicle", "car7", "--observer", "laptop", "--observer", "pit",
                       "--days", "30", "--router", "tls/192.168.1.10:7447", "--mounted-at", "/credentials")
    return directory, result


def test_it_writes_a_certificate_key_and_client_config_per_service_gateway_and_observer(made):
    directory, result = made
    assert result.returncode == 0, result.stderr
    for name in [*SERVICES, "laptop", "pit"]:
        assert common_name(directory / name / "cert.pem") == name
        assert stat.S_IMODE((directory / name / "key.pem").stat().st_mode) == 0o600
        assert (directory / name / "ca.pem").read_bytes() == (directory / "ca" / "ca.pem").read_bytes()
    assert not (directory / "sim").exists()
    assert "router, geolocation" in result.stdout and "laptop, pit" in result.stdout


def test_each_client_config_is_a_mutual_tls_client_of_the_router_with_its_files_where_it_is_mounted(made):
    directory, _ = made
    client = config(directory / "control" / "zenoh.json5")
    assert client["mode"] == "client" and client["connect"]["endpoints"] == ["tls/192.168.1.10:7447"]
    tls = client["transport"]["link"]["tls"]
    assert tls["enable_mtls"] is True
    assert (tls["connect_certificate"], tls["connect_private_key"], tls["root_ca_certificate"]) == (
        "/credentials/control/cert.pem", "/credentials/control/key.pem", "/credentials/control/ca.pem")
    zenoh.Config.from_file(str(directory / "control" / "zenoh.json5"))  # Zenoh reads it as it is


def test_the_routers_config_listens_on_tls_only_with_mutual_tls_and_the_access_rules(made):
    directory, _ = made
    router = config(directory / "router" / "zenohd.json5")
    assert router["mode"] == "router" and router["listen"]["endpoints"] == ["tls/0.0.0.0:7447"]
    assert router["transport"]["link"]["protocols"] == ["tls"]
    assert router["transport"]["link"]["tls"]["enable_mtls"] is True
    acl = router["access_control"]
    assert acl["default_permission"] == "deny"
    assert "coopdrive/car7/control/command" in next(rule["key_exprs"] for rule in acl["rules"]
                                                    if rule["id"] == "control publishes")
    zenoh.Config.from_file(str(directory / "router" / "zenohd.json5"))


def test_the_routers_certificate_answers_to_its_endpoints_host_and_to_localhost(made):
    directory, _ = made
    names = certificate(directory / "router" / "cert.pem").extensions.get_extension_for_class(
        x509.SubjectAlternativeName).value
    assert [str(address) for address in names.get_values_for_type(x509.IPAddress)] == ["192.168.1.10", "127.0.0.1"]
    assert names.get_values_for_type(x509.DNSName) == ["localhost"]


def test_days_sets_how_long_every_certificate_is_valid(made):
    directory, _ = made
    for name in ["ca", "router", "control", "laptop"]:
        issued = certificate(directory / name / ("ca.pem" if name == "ca" else "cert.pem"))
        validity = issued.not_valid_after_utc - issued.not_valid_before_utc
        assert datetime.timedelta(days=30) < validity < datetime.timedelta(days=30, minutes=10)


def test_it_refuses_to_overwrite_a_folder_of_credentials(made):
    directory, _ = made
    result = coopdrive("pki", "bus", str(directory), "--vehicle", "car7")
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "not overwriting" in result.stderr


@pytest.mark.parametrize("arguments, said", [
    (["--vehicle", "car/7"], "vehicle id 'car/7' must be"),
    (["--vehicle", "car7", "--observer", "control"], "observer name 'control' is taken"),
    (["--vehicle", "car7", "--days", "0"], "validity must be positive"),
    (["--vehicle", "car7", "--router", "tcp/127.0.0.1:7447"], "router endpoint 'tcp/127.0.0.1:7447' must be tls/"),
    (["--vehicle", "car7", "--router-listen", "tcp/0.0.0.0:7447"], "router listen endpoint 'tcp/0.0.0.0:7447' must"),
])
def test_a_bad_request_is_refused_in_one_line_and_writes_nothing(tmp_path, arguments, said):
    result = coopdrive("pki", "bus", str(tmp_path / "bus"), *arguments)
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and said in result.stderr
    assert not (tmp_path / "bus").exists()

