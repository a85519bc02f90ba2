"""HTTPS and mutual TLS on the gateway's server: with tls.client_ca, a client without a certificate gets nothing."""

import datetime
import ipaddress
import ssl

import httpx
import pytest
from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import NameOID
from ping_app import ping_app

from coopdrive.launch.ports import free_tcp_port
from coopdrive.services.gateway.config import TlsConfig
from coopdrive.services.gateway.server import HttpServerThread

REQUEST_TIMEOUT_S = 20.0
STOP_TIMEOUT_S = 5.0
VALIDITY = datetime.timedelta(days=1)


def issue(common_name: str, issuer_key=None, issuer_name=None, ca: bool = False, ip: str | None = None):
    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)])
    now = datetime.datetime.now(datetime.timezone.utc)
    builder = (x509.CertificateBuilder().subject_name(name).issuer_name(issuer_name or name)
               .public_key(key.public_key()).serial_number(x509.random_serial_number())
               .not_valid_before(now - VALIDITY).not_valid_after(now + VALIDITY)
               .add_extension(x509.BasicConstraints(ca=ca, path_length=None), critical=True))
    if ip is not None:
        builder = builder.add_extension(x509.SubjectAlternativeName([x509.IPAddress(ipaddress.ip_address(ip))]),
                                        critical=False)
    return key, builder.sign(issuer_key or key, hashes.SHA256())


def write(directory, stem: str, key, cert) -> tuple[str, str]:
    cert_path, key_path = directory / f"{stem}.pem", directory / f"{stem}-key.pem"
    cert_path.write_bytes(cert.public_bytes(serialization.Encoding.PEM))
    key_path.write_bytes(key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                           serialization.NoEncryption()))
    return str(cert_path), str(key_path)


@pytest.fixture
def pki(tmp_path):
    ca_key, ca = issue("vehicle CA", ca=True)
    ca_path, _ = write(tmp_path, "ca", ca_key, ca)
    server = write(tmp_path, "server", *issue("gateway", ca_key, ca.subject, ip="127.0.0.1"))
    client = write(tmp_path, "alice", *issue("alice", ca_key, ca.subject))
    return {"ca": ca_path, "server": server, "client": client}


def test_with_a_client_ca_only_clients_with_a_certificate_from_it_are_served(pki):
    port = free_tcp_port()
    tls = TlsConfig(certfile=pki["server"][0], keyfile=pki["server"][1], client_ca=pki["ca"])
    server = HttpServerThread(ping_app(), "127.0.0.1", port, tls)
    server.start()
    try:
        trusted = ssl.create_default_context(cafile=pki["ca"])
        with httpx.Client(verify=trusted, timeout=REQUEST_TIMEOUT_S) as anonymous:
            with pytest.raises(httpx.TransportError):
                anonymous.get(f"https://127.0.0.1:{port}/ping")
        trusted.load_cert_chain(*pki["client"])
        with httpx.Client(verify=trusted, timeout=REQUEST_TIMEOUT_S) as alice:
            assert alice.get(f"https://127.0.0.1:{port}/ping").json() == {"pong": True}
    finally:
        assert server.stop(STOP_TIMEOUT_S)
