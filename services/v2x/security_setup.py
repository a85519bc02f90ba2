"""The v2x service's security settings read from their files and checked before anything starts: each root
self-signed, each authority and ticket whose issuer this station knows signed by it, each ticket's key file its
ticket's key. Whatever is wrong is one line naming the setting, the file and the reason (SecuritySettingError), never
a traceback, and the service does not start.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from cryptography.hazmat.primitives import serialization

from coopdrive.runtime.config import ConfigError
from coopdrive.services.v2x.config import SecurityConfig
from coopdrive.v2x.security.certificate import Certificate, CertificateError
from coopdrive.v2x.security.crypto import load_private_key_pem
from coopdrive.v2x.security.pki import AUTHORITY_NAME, ROOT_NAME, Ticket

CERTIFICATE_SUFFIX = ".cert"
KEY_SUFFIX = ".key.pem"


class SecuritySettingError(ConfigError):
    """A security setting whose file cannot be used: `security.SETTING FILE: reason`."""


@dataclass
class SecurityMaterial:
    roots: list[Certificate]
    authorities: list[Certificate]
    # Our tickets with their keys, in file order (empty when this station does not sign).
    tickets: list[Ticket]


def load_security_material(config: SecurityConfig) -> SecurityMaterial:
    pki_dir = config.pki_dir
    roots = [_root("pki_dir", pki_dir / f"{ROOT_NAME}{CERTIFICATE_SUFFIX}")]
    roots += [_root("extra_trusted_roots", path) for path in config.extra_trusted_roots]
    issuers = {root.digest: root for root in roots}
    authority_files = [("pki_dir", pki_dir / f"{AUTHORITY_NAME}{CERTIFICATE_SUFFIX}")]
    authority_files += [("extra_authorities", path) for path in config.extra_authorities]
    authorities = []
    for setting, path in authority_files:
        authority = _issued(setting, path, issuers)
        if not authority.may_issue:
            raise SecuritySettingError(f"security.{setting} {path}: {authority.name} may not issue certificates")
        issuers[authority.digest] = authority
        authorities.append(authority)
    tickets = [] if config.ticket is None else _tickets(pki_dir / "vehicles" / config.ticket, issuers)
    return SecurityMaterial(roots, authorities, tickets)


def _certificate(setting: str, path: Path) -> Certificate:
    try:
        return Certificate.from_bytes(path.read_bytes())
    except OSError as error:
        raise SecuritySettingError(f"security.{setting} {path}: cannot be read ({error.strerror})") from None
    except CertificateError as error:
        raise SecuritySettingError(f"security.{setting} {path}: not a COER certificate ({error})") from None


def _root(setting: str, path: Path) -> Certificate:
    root = _certificate(setting, path)
    if not root.is_self_signed:
        raise SecuritySettingError(f"security.{setting} {path}: {root.name} is not self-signed, so no root")
    if not root.signature_is_from(None):
        raise SecuritySettingError(f"security.{setting} {path}: {root.name}'s self-signature does not verify")
    return root


def _issued(setting: str, path: Path, issuers: dict[bytes, Certificate]) -> Certificate:
    """A certificate whose issuer this station knows and whose signature that issuer made."""
    certificate = _certificate(setting, path)
    if certificate.is_self_signed:
        if not certificate.signature_is_from(None):
            raise SecuritySettingError(f"security.{setting} {path}: {certificate.name}'s self-signature does not "
                                       "verify")
        return certificate  # a root known, not trusted: what it issued chains to it and is refused as untrusted
    issuer = issuers.get(certificate.issuer_digest or b"")
    if issuer is None:
        # Known, not chained: what it issued is refused on the air as from an unknown issuer, never trusted.
        return certificate
    if not certificate.signature_is_from(issuer):
        raise SecuritySettingError(f"security.{setting} {path}: {certificate.name}'s signature by {issuer.name} "
                                   "does not verify")
    return certificate


def _tickets(folder: Path, issuers: dict[bytes, Certificate]) -> list[Ticket]:
    tickets = []
    for certificate_path in sorted(folder.glob(f"ticket-*{CERTIFICATE_SUFFIX}")):
        ticket = _issued("ticket", certificate_path, issuers)
        key_path = certificate_path.with_name(certificate_path.name.removesuffix(CERTIFICATE_SUFFIX) + KEY_SUFFIX)
        try:
            key = load_private_key_pem(key_path.read_bytes())
        except OSError as error:
            raise SecuritySettingError(f"security.ticket {key_path}: cannot be read ({error.strerror})") from None
        except ValueError as error:
            reason = str(error).split(".")[0]
            raise SecuritySettingError(f"security.ticket {key_path}: not an EC private key in PEM ({reason})") from None
        if _public_bytes(key.public_key()) != _public_bytes(ticket.public_key):
            raise SecuritySettingError(f"security.ticket {key_path}: not the key of {certificate_path.name}")
        tickets.append((ticket, key))
    return tickets


def _public_bytes(key) -> bytes:
    return key.public_bytes(serialization.Encoding.X962, serialization.PublicFormat.CompressedPoint)
