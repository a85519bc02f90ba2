"""Certificates to trust, loaded from files: `coopdrive v2x decode --trust FILE_OR_DIR`.

    store = trust_store([Path("eu-trust-list/"), Path("my-root.oer")])

Each file holds one certificate in canonical COER (EtsiTs103097Certificate), e.g. the root and authority
certificates of the EU trust list, or `root.cert` / `aa.cert` of `coopdrive pki init`. A directory contributes
its files ending in .cert, .oer or .coer (not its subdirectories). Self-signed certificates become trusted
roots (their self-signature checked); issuing certificates become known authorities; authorisation tickets are
remembered like tickets heard on the air. A file that is no certificate raises TrustFileError naming it.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from coopdrive.v2x.security.certificate import Certificate, CertificateError
from coopdrive.v2x.security.store import CertificateStore

CERTIFICATE_SUFFIXES = (".cert", ".oer", ".coer")


class TrustFileError(ValueError):
    """A --trust path that is missing or holds something other than a certificate."""


def certificate_files(paths: Iterable[Path]) -> list[Path]:
    files: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            files += sorted(entry for entry in path.iterdir()
                            if entry.is_file() and entry.suffix.lower() in CERTIFICATE_SUFFIXES)
        elif path.is_file():
            files.append(path)
        else:
            raise TrustFileError(f"{path}: no such file or directory")
    return files


def trust_store(paths: Iterable[Path]) -> CertificateStore:
    certificates = []
    for path in certificate_files(paths):
        try:
            certificates.append(Certificate.from_bytes(path.read_bytes()))
        except (OSError, CertificateError) as error:
            raise TrustFileError(f"{path}: not a COER certificate ({error})") from None
    store = CertificateStore()
    # Roots first, so that authorities and tickets can be chained to them whatever the file order.
    for certificate in sorted(certificates, key=lambda c: (not c.is_self_signed, not c.may_issue)):
        try:
            if certificate.is_self_signed:
                store.trust_root(certificate)
            elif certificate.may_issue:
                store.add_authority(certificate)
            else:
                store.remember(certificate)
        except CertificateError as error:
            raise TrustFileError(f"{certificate.name}: {error}") from None
    return store
