"""A certificate chain made by FlexStack's own certificate code (root CA -> authorisation authority -> one
authorisation ticket), for the signed live exchange. Run by .venv-peers/bin/python only (see flexstack_peer.py).

The chain is FlexStack's: it signs and hashes its certificates its own way (the note
/work/shared/notes/v2x-peers.md: a plain SHA-256 of the to-be-signed data, digests over the certificate as sent),
which is exactly what the live test shows a standard verifier refusing.
"""

from pathlib import Path

from flexstack.security.certificate import OwnCertificate
from flexstack.security.ecdsa_backend import PythonECDSABackend

PSIDS = (36, 37)  # CAM, DENM
VALIDITY = ("years", 5)
# What each file of the chain holds; flexstack_peer.py reads the same names.
CHAIN_FILES = {"root": "root.cert", "aa": "aa.cert", "at": "at.cert", "at_key": "at.pem"}
ROOT_MIN_CHAIN, AA_MIN_CHAIN = 2, 1
NO_CRACA = b"\x00\x00\x00"


def _tbs(name: str, issue_permissions: list | None = None) -> dict:
    """A ToBeSignedCertificate (TS 103 097 6): issuing certificates carry certIssuePermissions, a ticket
    appPermissions; the verification key is filled in by FlexStack when it makes the key pair."""
    tbs = {"id": ("name", name), "cracaId": NO_CRACA, "crlSeries": 0,
           "validityPeriod": {"start": 0, "duration": VALIDITY},
           "verifyKeyIndicator": ("verificationKey", ("ecdsaNistP256", ("fill", None)))}
    if issue_permissions is None:
        tbs["appPermissions"] = [{"psid": psid} for psid in PSIDS]
    else:
        tbs["certIssuePermissions"] = issue_permissions
    return tbs


def _may_issue(subjects, min_chain_length: int) -> list:
    return [{"subjectPermissions": subjects, "minChainLength": min_chain_length, "chainLengthRange": 0,
             "eeType": (b"\x00", 1)}]


def make_chain(directory: Path) -> None:
    """Writes root.cert, aa.cert, at.cert (COER) and at.pem (the ticket's private key) into directory."""
    directory.mkdir(parents=True, exist_ok=True)
    backend = PythonECDSABackend()
    root = OwnCertificate.initialize_certificate(
        backend=backend, to_be_signed_certificate=_tbs("live-root", _may_issue(("all", None), ROOT_MIN_CHAIN)),
        issuer=None)
    explicit = ("explicit", [{"psid": psid} for psid in PSIDS])
    authority = OwnCertificate.initialize_certificate(
        backend=backend, to_be_signed_certificate=_tbs("live-aa", _may_issue(explicit, AA_MIN_CHAIN)), issuer=root)
    ticket = OwnCertificate.initialize_certificate(backend=backend, to_be_signed_certificate=_tbs("live-at"),
                                                   issuer=authority)
    for name, certificate in (("root", root), ("aa", authority), ("at", ticket)):
        (directory / CHAIN_FILES[name]).write_bytes(certificate.encode())
    (directory / CHAIN_FILES["at_key"]).write_bytes(backend.export_signing_key(ticket.key_id))
