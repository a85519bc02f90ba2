"""The vehicle's bus certificate authority: an X.509 CA whose certificates Zenoh's TLS links check both ways (mutual
TLS). A certificate's common name is who its holder is on the bus (a service's name, "gateway", an observer's name):
the router's access control matches its rules to that name.

Keys are ECDSA P-256 in PKCS #8 PEM, which Zenoh's TLS (rustls) reads. A leaf certificate carries the names it may be
reached at (subject alternative names) when it is also a server's (the router's), so a client that checks the name
it connected to (`verify_name_on_connect`) accepts it.
"""

from __future__ import annotations

import datetime
import ipaddress
from dataclasses import dataclass
from pathlib import Path

from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

# A certificate is valid from a little before it was made: a second computer whose clock lags by this much
# still accepts it.
CLOCK_SKEW_ALLOWANCE_S = 300


@dataclass(frozen=True)
class BusAuthority:
    certificate: x509.Certificate
    key: ec.EllipticCurvePrivateKey

    @classmethod
    def create(cls, common_name: str, days: float, now: datetime.datetime | None = None) -> BusAuthority:
        """A new self-signed CA valid for `days` from `now` (default: the present)."""
        if days <= 0:
            raise ValueError(f"a certificate's validity must be positive, not {days} days")
        key = ec.generate_private_key(ec.SECP256R1())
        name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)])
        not_before, not_after = _validity(now, days)
        certificate = (
            x509.CertificateBuilder().subject_name(name).issuer_name(name).public_key(key.public_key())
            .serial_number(x509.random_serial_number()).not_valid_before(not_before).not_valid_after(not_after)
            .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
            .add_extension(x509.KeyUsage(digital_signature=True, key_cert_sign=True, crl_sign=True,
                                         content_commitment=False, key_encipherment=False, data_encipherment=False,
                                         key_agreement=False, encipher_only=False, decipher_only=False), critical=True)
            .add_extension(x509.SubjectKeyIdentifier.from_public_key(key.public_key()), critical=False)
            .sign(key, hashes.SHA256()))
        return cls(certificate, key)

    @classmethod
    def load(cls, certificate_path: Path, key_path: Path) -> BusAuthority:
        certificate = x509.load_pem_x509_certificate(certificate_path.read_bytes())
        key = serialization.load_pem_private_key(key_path.read_bytes(), password=None)
        return cls(certificate, key)

    @property
    def common_name(self) -> str:
        return self.certificate.subject.get_attributes_for_oid(NameOID.COMMON_NAME)[0].value

    def issue(self, common_name: str, days: float, hosts: tuple[str, ...] = (),
              now: datetime.datetime | None = None) -> tuple[x509.Certificate, ec.EllipticCurvePrivateKey]:
        """A certificate and its new key for `common_name`, valid for `days` from `now` (in the past: an expired
        one), usable to connect and, given `hosts` (DNS names or IP addresses), to be listened on at those."""
        if days <= 0:
            raise ValueError(f"a certificate's validity must be positive, not {days} days")
        if not common_name:
            raise ValueError("a certificate needs a common name")
        key = ec.generate_private_key(ec.SECP256R1())
        not_before, not_after = _validity(now, days)
        usages = [ExtendedKeyUsageOID.CLIENT_AUTH] + ([ExtendedKeyUsageOID.SERVER_AUTH] if hosts else [])
        builder = (
            x509.CertificateBuilder()
            .subject_name(x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)]))
            .issuer_name(self.certificate.subject).public_key(key.public_key())
            .serial_number(x509.random_serial_number()).not_valid_before(not_before).not_valid_after(not_after)
            .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True)
            .add_extension(x509.ExtendedKeyUsage(usages), critical=False)
            .add_extension(x509.AuthorityKeyIdentifier.from_issuer_public_key(self.key.public_key()), critical=False))
        if hosts:
            builder = builder.add_extension(x509.SubjectAlternativeName([_general_name(h) for h in hosts]),
                                            critical=False)
        return builder.sign(self.key, hashes.SHA256()), key

    def write(self, certificate_path: Path, key_path: Path) -> None:
        write_pair(self.certificate, self.key, certificate_path, key_path)


def write_pair(certificate: x509.Certificate, key: ec.EllipticCurvePrivateKey, certificate_path: Path,
               key_path: Path) -> None:
    """The certificate in PEM, and its key in PKCS #8 PEM readable by its owner only."""
    certificate_path.write_bytes(certificate.public_bytes(serialization.Encoding.PEM))
    key_path.touch(mode=0o600)
    key_path.chmod(0o600)
    key_path.write_bytes(key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                           serialization.NoEncryption()))


def _validity(now: datetime.datetime | None, days: float) -> tuple[datetime.datetime, datetime.datetime]:
    start = now or datetime.datetime.now(datetime.timezone.utc)
    return start - datetime.timedelta(seconds=CLOCK_SKEW_ALLOWANCE_S), start + datetime.timedelta(days=days)


def _general_name(host: str) -> x509.GeneralName:
    try:
        return x509.IPAddress(ipaddress.ip_address(host))
    except ValueError:
        return x509.DNSName(host)
