"""ECDSA on NIST P-256 and brainpoolP256r1 with SHA-256, hashed the IEEE 1609.2 way, via `cryptography`.

IEEE 1609.2 (5.3.1) signs Hash(Hash(tbs) || Hash(signer)) where signer is the canonical OER encoding of the
signer's certificate, or the empty string for a self-signed root. Keys travel as compressed points, the
signature as (r as x-only point, s).
"""

from __future__ import annotations

import enum
import hashlib

from cryptography.exceptions import InvalidSignature
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.hazmat.primitives.asymmetric.utils import (
    Prehashed, decode_dss_signature, encode_dss_signature)

HASHED_ID8_SIZE = 8
HASHED_ID3_SIZE = 3
COORDINATE_SIZE = 32
_COMPRESSED_EVEN, _COMPRESSED_ODD = 0x02, 0x03
_PREHASHED = ec.ECDSA(Prehashed(hashes.SHA256()))
# EccP256CurvePoint forms that carry r (its x coordinate); "fill" carries nothing.
_R_FORMS = ("x-only", "compressed-y-0", "compressed-y-1", "uncompressedP256")


class Curve(enum.Enum):
    """Signature curves of TS 103 097 v1.3.1; values are the ASN.1 choice names of PublicVerificationKey."""

    NIST_P256 = "ecdsaNistP256"
    BRAINPOOL_P256R1 = "ecdsaBrainpoolP256r1"

    @property
    def signature_choice(self) -> str:
        return f"{self.value}Signature"

    def ec_curve(self) -> ec.EllipticCurve:
        return ec.SECP256R1() if self is Curve.NIST_P256 else ec.BrainpoolP256R1()


CURVE_OF_KEY_CHOICE = {curve.value: curve for curve in Curve}
CURVE_OF_SIGNATURE_CHOICE = {curve.signature_choice: curve for curve in Curve}


def sha256(data: bytes) -> bytes:
    return hashlib.sha256(data).digest()


def hashed_id8(encoded_certificate: bytes) -> bytes:
    """HashedId8: the low-order 8 bytes of SHA-256 over the certificate's canonical OER encoding."""
    return sha256(encoded_certificate)[-HASHED_ID8_SIZE:]


def hashed_id3(encoded_certificate: bytes) -> bytes:
    return sha256(encoded_certificate)[-HASHED_ID3_SIZE:]


def data_digest(tbs: bytes, signer_certificate: bytes | None) -> bytes:
    """Hash(Hash(tbs) || Hash(signer certificate, or empty for self-signed)), IEEE 1609.2 5.3.1."""
    return sha256(sha256(tbs) + sha256(signer_certificate or b""))


def generate_key(curve: Curve) -> ec.EllipticCurvePrivateKey:
    return ec.generate_private_key(curve.ec_curve())


def curve_of_key(key: ec.EllipticCurvePrivateKey | ec.EllipticCurvePublicKey) -> Curve:
    name = key.curve.name
    if name == ec.SECP256R1.name:
        return Curve.NIST_P256
    if name == ec.BrainpoolP256R1.name:
        return Curve.BRAINPOOL_P256R1
    raise ValueError(f"curve {name} is not allowed by TS 103 097 v1.3.1 here")


def public_key_choice(key: ec.EllipticCurvePublicKey, uncompressed: bool = False) -> tuple[str, tuple[str, object]]:
    """PublicVerificationKey value for asn1tools: (curve choice, compressed EccP256CurvePoint); uncompressed, as
    another stack sends its keys (a certificate's canonical form compresses it again, canonical.py)."""
    if uncompressed:
        point = key.public_bytes(serialization.Encoding.X962, serialization.PublicFormat.UncompressedPoint)
        return curve_of_key(key).value, ("uncompressedP256", {"x": point[1:1 + COORDINATE_SIZE],
                                                              "y": point[1 + COORDINATE_SIZE:]})
    point = key.public_bytes(serialization.Encoding.X962, serialization.PublicFormat.CompressedPoint)
    form = "compressed-y-0" if point[0] == _COMPRESSED_EVEN else "compressed-y-1"
    return curve_of_key(key).value, (form, point[1:])


def public_key_from_choice(choice: tuple[str, tuple[str, object]]) -> ec.EllipticCurvePublicKey:
    """The key of a PublicVerificationKey; raises ValueError for curves or point forms not supported."""
    curve_name, (form, point) = choice
    curve = CURVE_OF_KEY_CHOICE.get(curve_name)
    if curve is None:
        raise ValueError(f"verification key curve {curve_name}")
    if form == "compressed-y-0":
        encoded = bytes([_COMPRESSED_EVEN]) + point
    elif form == "compressed-y-1":
        encoded = bytes([_COMPRESSED_ODD]) + point
    elif form == "uncompressedP256":
        encoded = b"\x04" + point["x"] + point["y"]
    else:
        raise ValueError(f"verification key point form {form}")
    return ec.EllipticCurvePublicKey.from_encoded_point(curve.ec_curve(), encoded)


def sign_digest(key: ec.EllipticCurvePrivateKey, digest: bytes) -> tuple[str, dict]:
    """Signature value for asn1tools: r as an x-only point (IEEE 1609.2 allows it and it needs no y)."""
    r, s = decode_dss_signature(key.sign(digest, _PREHASHED))
    return curve_of_key(key).signature_choice, {
        "rSig": ("x-only", r.to_bytes(COORDINATE_SIZE, "big")), "sSig": s.to_bytes(COORDINATE_SIZE, "big")}


def verify_digest(key: ec.EllipticCurvePublicKey, signature: tuple[str, dict], digest: bytes) -> bool:
    """True when the signature is on this key's curve and valid for the digest.

    rSig may come in any form IEEE 1609.2 allows (x-only, compressed, uncompressed): only its x coordinate is
    r. Real stations send the compressed forms (the signed CAMs in shared/data/v2x do), so all are accepted;
    a packet rewritten into another form of the same r stays valid, which is why nothing here identifies
    packets by the hash of their bytes.
    """
    choice, value = signature
    if CURVE_OF_SIGNATURE_CHOICE.get(choice) is not curve_of_key(key):
        return False
    form, point = value["rSig"]
    if form not in _R_FORMS:
        return False
    r_bytes = point["x"] if form == "uncompressedP256" else point
    r, s = int.from_bytes(r_bytes, "big"), int.from_bytes(value["sSig"], "big")
    try:
        key.verify(encode_dss_signature(r, s), digest, _PREHASHED)
    except (InvalidSignature, ValueError):
        return False
    return True


def private_key_pem(key: ec.EllipticCurvePrivateKey) -> bytes:
    return key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                             serialization.NoEncryption())


def load_private_key_pem(data: bytes) -> ec.EllipticCurvePrivateKey:
    key = serialization.load_pem_private_key(data, password=None)
    if not isinstance(key, ec.EllipticCurvePrivateKey):
        raise ValueError("not an EC private key")
    curve_of_key(key)
    return key
