"""A certificate's canonical form, the one its HashedId8 and the signer hash of a signature are taken over.

IEEE 1609.2-2016 6.4.3 (which TS 103 097 v1.3.1 clause 6 applies): a certificate is hashed with every
EccP256CurvePoint of its public keys in compressed form and the r of its signature as x-only. A station may send
a key uncompressed (another open C++ stack does); its digest is still that of the compressed form, so two stations
that send the same certificate in different forms name it by one digest. Certificates in canonical form (ours, and
those in the real captures: compressed keys, x-only r) hash as received.
"""

from __future__ import annotations

UNCOMPRESSED_FORMS = ("uncompressedP256", "uncompressedP384")
COMPRESSED_FORMS = ("compressed-y-0", "compressed-y-1")
X_ONLY = "x-only"


def canonical_certificate(value: dict) -> dict:
    """`value` (a decoded EtsiTs103097Certificate) in canonical form; `value` itself is left as it is."""
    tbs = dict(value["toBeSigned"])
    indicator, key = tbs["verifyKeyIndicator"]
    if indicator == "verificationKey":
        curve, point = key
        tbs["verifyKeyIndicator"] = (indicator, (curve, _compressed(point)))
    encryption_key = tbs.get("encryptionKey")
    if encryption_key is not None:
        curve, point = encryption_key["publicKey"]
        tbs["encryptionKey"] = {**encryption_key, "publicKey": (curve, _compressed(point))}
    canonical = {**value, "toBeSigned": tbs}
    if "signature" in value:
        choice, signature = value["signature"]
        canonical["signature"] = (choice, {**signature, "rSig": _x_only(signature["rSig"])})
    return canonical


def _compressed(point: tuple[str, object]) -> tuple[str, object]:
    form, coordinates = point
    if form not in UNCOMPRESSED_FORMS:
        return point
    x, y = coordinates["x"], coordinates["y"]
    return ("compressed-y-1" if y[-1] & 1 else "compressed-y-0"), x


def _x_only(point: tuple[str, object]) -> tuple[str, object]:
    form, coordinates = point
    if form in COMPRESSED_FORMS:
        return X_ONLY, coordinates
    if form in UNCOMPRESSED_FORMS:
        return X_ONLY, coordinates["x"]
    return point
