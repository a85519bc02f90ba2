"""Why a session over mutual TLS could not open, in the user's terms.

When the router refuses a client's certificate, Zenoh tells the client only that it could not connect to any
endpoint. The usual reasons are on the client's side and can be read off its own files: no certificate, one that has
expired or is not yet valid, one that another CA signed. This names the first of those it finds.
"""

from __future__ import annotations

import datetime
import json
from pathlib import Path

import zenoh
from cryptography import x509
from cryptography.exceptions import InvalidSignature
from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.bus.credentials_error import REMEDY



def credentials_problem(config: zenoh.Config, now: datetime.datetime | None = None) -> str | None:
    """What is wrong with the client certificate a TLS config names; None when nothing is (the router may be down)."""
    tls = json.loads(config.get_json("transport/link/tls"))
    endpoints = json.loads(config.get_json("connect/endpoints")) or []
    if not any(str(endpoint).startswith("tls/") for endpoint in endpoints):
        return None
    certificate_path, authority_path = tls.get("connect_certificate"), tls.get("root_ca_certificate")
    if not certificate_path:
        return f"no client certificate in the TLS config (connect_certificate): {REMEDY}"
    try:
        certificate = x509.load_pem_x509_certificate(Path(certificate_path).read_bytes())
        authority = x509.load_pem_x509_certificate(Path(authority_path).read_bytes()) if authority_path else None
    except (OSError, ValueError) as error:
        return f"cannot read the bus credentials: {error}: {REMEDY}"
    now = now or datetime.datetime.now(datetime.timezone.utc)
    if now > certificate.not_valid_after_utc:
        return (f"certificate {certificate_path} expired on {certificate.not_valid_after_utc:%Y-%m-%d %H:%M} UTC: "
                f"{REMEDY}")
    if now < certificate.not_valid_before_utc:
        starts = f"{certificate.not_valid_before_utc:%Y-%m-%d %H:%M}"
        return f"certificate {certificate_path} is not valid before {starts} UTC (is this computer's clock right?)"
    if authority is not None and not _signed_by(certificate, authority):
        return f"certificate {certificate_path} is not signed by the bus CA {authority_path}: {REMEDY}"
    return None


def _signed_by(certificate: x509.Certificate, authority: x509.Certificate) -> bool:
    key = authority.public_key()
    if not isinstance(key, ec.EllipticCurvePublicKey):
        return True  # not one of ours: the router will judge it
    try:
        key.verify(certificate.signature, certificate.tbs_certificate_bytes,
                   ec.ECDSA(certificate.signature_hash_algorithm))
    except InvalidSignature:
        return False
    return True
