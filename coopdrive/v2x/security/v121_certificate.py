"""Certificates, keys and signatures of ETSI TS 103 097 v1.2.1 (clauses 4.2 and 6), read from their wire bytes.

    certificate = read_certificate(PresentationReader(data))   # V2xDecodeError when malformed
    certificate.digest                                          # HashedId8, clause 4.2.12
    verify_ecdsa(certificate.public_key, signature, signed_bytes)

A certificate is version 2 | signer_info | subject_info | subject_attributes<var> | validity_restrictions<var> |
signature. Its HashedId8 is the low-order 8 octets of SHA-256 over its encoding with the signature's R point as
x_coordinate_only (clause 4.2.12: a certificate keeps one digest whichever form of R it travels with). The signature
of a v1.2.1 message or certificate is plain ECDSA with SHA-256 over the signed bytes (no IEEE 1609.2 double hash).
"""

from __future__ import annotations

from dataclasses import dataclass

from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.v2x.security.crypto import Curve, hashed_id8, sha256, verify_digest
from coopdrive.v2x.security.v121_reader import (
    CERTIFICATE_VERSION, FIELD_SIZE, HASHED_ID8_SIZE, EccPointType, PresentationReader, PublicKeyAlgorithm,
    RegionType, SignerInfoType, SubjectAttributeType, ValidityRestrictionType, malformed)

# CircularRegion: a TwoDLocation (two int32) and a uint16 radius; a rectangle two TwoDLocations;
# IdentifiedRegion: a dictionary octet and a uint16 region id before its IntX local region.
_CIRCLE_SIZE, _IDENTIFIED_REGION_HEAD_SIZE = 10, 3
_TIME32_SIZE, _DURATION_SIZE = 4, 2
_ASSURANCE_SIZE = 1
# Duration (clause 4.2.19): 3 bits of unit, 13 of value; units in seconds (the last: years of 31556925 s).
_DURATION_VALUE_BITS = 13
_DURATION_UNIT_S = (1, 60, 3600, 60 * 3600, 31_556_925)
_SIGNATURE_CHOICE = Curve.NIST_P256.signature_choice
# EccPoint forms that carry a verification key; a key cannot be rebuilt from its x coordinate only.
_KEY_PREFIX = {EccPointType.COMPRESSED_LSB_Y_0: b"\x02", EccPointType.COMPRESSED_LSB_Y_1: b"\x03",
               EccPointType.UNCOMPRESSED: b"\x04"}


@dataclass(frozen=True, slots=True)
class EccPoint:
    form: int
    x: bytes
    y: bytes = b""


@dataclass(frozen=True, slots=True)
class V121Signature:
    """An ECDSA NIST P-256 signature (algorithm 0); other algorithms are kept by number, unusable."""

    algorithm: int
    r: EccPoint | None = None
    s: bytes = b""

    @property
    def canonical_bytes(self) -> bytes:
        """The encoding with R as x_coordinate_only (what the HashedId8 of a certificate is taken over)."""
        return bytes([self.algorithm, EccPointType.X_COORDINATE_ONLY]) + self.r.x + self.s


@dataclass(frozen=True, slots=True)
class V121Certificate:
    signer_type: int
    # The issuer's HashedId8 (signer certificate_digest_with_sha256); None for self-signed roots.
    issuer_digest: bytes | None
    subject_type: int
    verification_key: EccPoint | None
    its_aids: frozenset[int]
    # Time32: seconds since 2004-01-01 TAI; None when the certificate gives no such bound.
    start_s: int | None
    end_s: int | None
    signature: V121Signature
    # The bytes its issuer signed, and the encoding its HashedId8 is taken over.
    signed_bytes: bytes
    canonical_bytes: bytes

    @property
    def digest(self) -> bytes:
        return hashed_id8(self.canonical_bytes)

    @property
    def public_key(self) -> ec.EllipticCurvePublicKey:
        """The verification key; ValueError when it has none usable (another algorithm, a point off the curve)."""
        point = self.verification_key
        if point is None or point.form not in _KEY_PREFIX:
            raise ValueError("no ECDSA NIST P-256 verification key")
        return ec.EllipticCurvePublicKey.from_encoded_point(ec.SECP256R1(), _KEY_PREFIX[point.form] + point.x + point.y)


def read_ecc_point(reader: PresentationReader) -> EccPoint:
    form = reader.u8()
    x = reader.fixed(FIELD_SIZE)
    if form == EccPointType.UNCOMPRESSED:
        return EccPoint(form, x, reader.fixed(FIELD_SIZE))
    if form in (EccPointType.X_COORDINATE_ONLY, EccPointType.COMPRESSED_LSB_Y_0, EccPointType.COMPRESSED_LSB_Y_1):
        return EccPoint(form, x)
    return EccPoint(form, x, reader.var_opaque())


def read_signature(reader: PresentationReader) -> V121Signature:
    algorithm = reader.u8()
    if algorithm != PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256:
        reader.var_opaque()
        return V121Signature(algorithm)
    return V121Signature(algorithm, read_ecc_point(reader), reader.fixed(FIELD_SIZE))


def verify_ecdsa(key: ec.EllipticCurvePublicKey, signature: V121Signature, signed_bytes: bytes) -> bool:
    """ECDSA NIST P-256 with SHA-256 over signed_bytes; r is R's x coordinate in whichever form it came."""
    if signature.algorithm != PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256 or \
            signature.r.form not in (EccPointType.X_COORDINATE_ONLY, *_KEY_PREFIX):
        return False
    choice = (_SIGNATURE_CHOICE, {"rSig": ("x-only", signature.r.x), "sSig": signature.s})
    return verify_digest(key, choice, sha256(signed_bytes))


def read_public_key(reader: PresentationReader) -> tuple[int, EccPoint | None]:
    algorithm = reader.u8()
    if algorithm == PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256:
        return algorithm, read_ecc_point(reader)
    if algorithm == PublicKeyAlgorithm.ECIES_NISTP256:
        reader.u8()  # the supported symmetric algorithm
        return algorithm, read_ecc_point(reader)
    reader.var_opaque()
    return algorithm, None


def read_certificate_signer(reader: PresentationReader) -> tuple[int, bytes | None]:
    """A certificate's signer: itself or its issuer's digest (a certificate inside a certificate is refused, which
    also bounds the nesting a crafted packet could ask for)."""
    kind = reader.u8()
    if kind == SignerInfoType.SELF:
        return kind, None
    if kind == SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256:
        return kind, reader.fixed(HASHED_ID8_SIZE)
    if kind == SignerInfoType.CERTIFICATE_DIGEST_WITH_OTHER_ALGORITHM:
        reader.u8()
        return kind, reader.fixed(HASHED_ID8_SIZE)
    raise malformed(f"certificate signer type {kind}")


def _read_attributes(reader: PresentationReader) -> tuple[EccPoint | None, frozenset[int]]:
    key, its_aids = None, set()
    while not reader.at_end:
        kind = reader.u8()
        if kind in (SubjectAttributeType.VERIFICATION_KEY, SubjectAttributeType.ENCRYPTION_KEY):
            algorithm, point = read_public_key(reader)
            if kind == SubjectAttributeType.VERIFICATION_KEY and \
                    algorithm == PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256:
                key = point
        elif kind == SubjectAttributeType.ASSURANCE_LEVEL:
            reader.fixed(_ASSURANCE_SIZE)
        elif kind == SubjectAttributeType.RECONSTRUCTION_VALUE:
            read_ecc_point(reader)
        elif kind == SubjectAttributeType.ITS_AID_LIST:
            aids = reader.var_reader()
            while not aids.at_end:
                its_aids.add(aids.length())
        elif kind == SubjectAttributeType.ITS_AID_SSP_LIST:
            aids = reader.var_reader()
            while not aids.at_end:
                its_aids.add(aids.length())
                aids.var_opaque()
        else:
            reader.var_opaque()
    return key, frozenset(its_aids)


def _skip_region(reader: PresentationReader) -> None:
    kind = reader.u8()
    if kind == RegionType.CIRCLE:
        reader.fixed(_CIRCLE_SIZE)
    elif kind in (RegionType.RECTANGLE, RegionType.POLYGON):
        reader.var_opaque()
    elif kind == RegionType.ID:
        reader.fixed(_IDENTIFIED_REGION_HEAD_SIZE)
        reader.length()
    elif kind != RegionType.NONE:
        reader.var_opaque()


def _read_validity(reader: PresentationReader) -> tuple[int | None, int | None]:
    start_s = end_s = None
    while not reader.at_end:
        kind = reader.u8()
        if kind == ValidityRestrictionType.TIME_END:
            end_s = reader.uint(_TIME32_SIZE)
        elif kind == ValidityRestrictionType.TIME_START_AND_END:
            start_s, end_s = reader.uint(_TIME32_SIZE), reader.uint(_TIME32_SIZE)
        elif kind == ValidityRestrictionType.TIME_START_AND_DURATION:
            start_s, duration = reader.uint(_TIME32_SIZE), reader.uint(_DURATION_SIZE)
            unit = duration >> _DURATION_VALUE_BITS
            if unit >= len(_DURATION_UNIT_S):
                raise malformed(f"duration unit {unit}")
            end_s = start_s + (duration & ((1 << _DURATION_VALUE_BITS) - 1)) * _DURATION_UNIT_S[unit]
        elif kind == ValidityRestrictionType.REGION:
            _skip_region(reader)
        else:
            reader.var_opaque()
    return start_s, end_s


def read_certificate(reader: PresentationReader) -> V121Certificate:
    start = reader.offset
    version = reader.u8()
    if version != CERTIFICATE_VERSION:
        raise malformed(f"certificate version {version}")
    signer_type, issuer_digest = read_certificate_signer(reader)
    subject_type = reader.u8()
    reader.var_opaque()  # subject name
    key, its_aids = _read_attributes(reader.var_reader())
    start_s, end_s = _read_validity(reader.var_reader())
    signed_bytes = reader.data[start:reader.offset]
    signature = read_signature(reader)
    if signature.r is None:
        raise malformed(f"certificate signature algorithm {signature.algorithm}")
    return V121Certificate(signer_type, issuer_digest, subject_type, key, its_aids, start_s, end_s, signature,
                           signed_bytes, signed_bytes + signature.canonical_bytes)

