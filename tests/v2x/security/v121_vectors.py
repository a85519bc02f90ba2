"""TS 103 097 v1.2.1 test vectors written from the standard with keys of our own: certificates (clause 6) and
secured GeoNetworking packets (clause 5), signed by ECDSA NIST P-256 with SHA-256.

    issuer = V121Key.generate()
    ticket = issuer.issue(V121Key.generate())                  # an authorisation ticket, as V121Ticket
    packet = secure(gn_v0_packet, ticket, Signer.CERTIFICATE, generation_time_us)
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.hazmat.primitives.asymmetric.utils import decode_dss_signature

from coopdrive.v2x.geonet import BASIC_HEADER_SIZE, BasicNextHeader, with_basic_next_header
from coopdrive.v2x.security.crypto import hashed_id8
from coopdrive.v2x.security.profile import PSID_CAM, PSID_DENM
from coopdrive.v2x.security.v121_reader import (
    CERTIFICATE_VERSION, FIELD_SIZE, PROTOCOL_VERSION, EccPointType, HeaderFieldType, PayloadType,
    PublicKeyAlgorithm, SignerInfoType, SubjectAttributeType, TrailerFieldType, ValidityRestrictionType,
    encode_length)

# NIST P-256: y^2 = x^3 - 3x + b (mod p); p = 3 (mod 4), so a square root is a power.
P256_P = 2**256 - 2**224 + 2**192 + 2**96 - 1
P256_B = 0x5AC635D8AA3A93E7B3EBBD55769886BC651D06B0CC53B0F63BCE3C3E27D2604B
SUBJECT_AUTHORIZATION_TICKET, SUBJECT_AUTHORIZATION_AUTHORITY = 1, 2
ASSURANCE_LEVEL = b"\x00"
# Time32 seconds since 2004: 2020-01-01 to 2040-01-01 (about).
VALID_FROM_S, VALID_UNTIL_S = 504_921_600, 1_136_073_600
_SIGNING = ec.ECDSA(hashes.SHA256())


class Signer(enum.Enum):
    CERTIFICATE = SignerInfoType.CERTIFICATE
    DIGEST = SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256
    CHAIN = SignerInfoType.CERTIFICATE_CHAIN


def var(data: bytes) -> bytes:
    return encode_length(len(data)) + data


def public_point(key: ec.EllipticCurvePublicKey, form: EccPointType) -> bytes:
    uncompressed = key.public_bytes(serialization.Encoding.X962, serialization.PublicFormat.UncompressedPoint)
    x, y = uncompressed[1:1 + FIELD_SIZE], uncompressed[1 + FIELD_SIZE:]
    if form == EccPointType.UNCOMPRESSED:
        return bytes([form]) + x + y
    return bytes([EccPointType.COMPRESSED_LSB_Y_0 + (y[-1] & 1)]) + x


def signature(key: ec.EllipticCurvePrivateKey, signed: bytes, r_form: EccPointType) -> bytes:
    """Signature: algorithm 0, R in the given form (its y recovered from x = r on the curve), s."""
    r, s = decode_dss_signature(key.sign(signed, _SIGNING))
    y = pow((r ** 3 - 3 * r + P256_B) % P256_P, (P256_P + 1) // 4, P256_P)
    x_bytes, y_bytes = r.to_bytes(FIELD_SIZE, "big"), y.to_bytes(FIELD_SIZE, "big")
    if r_form == EccPointType.UNCOMPRESSED:
        point = bytes([r_form]) + x_bytes + y_bytes
    elif r_form == EccPointType.X_COORDINATE_ONLY:
        point = bytes([r_form]) + x_bytes
    else:
        point = bytes([EccPointType.COMPRESSED_LSB_Y_0 + (y & 1)]) + x_bytes
    return bytes([PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256]) + point + s.to_bytes(FIELD_SIZE, "big")


def canonical_digest(certificate: bytes, signed_size: int) -> bytes:
    """HashedId8 over the certificate with R as x_coordinate_only (clause 4.2.12)."""
    tail = certificate[signed_size:]
    x_only = tail[:1] + bytes([EccPointType.X_COORDINATE_ONLY]) + tail[2:2 + FIELD_SIZE] + tail[-FIELD_SIZE:]
    return hashed_id8(certificate[:signed_size] + x_only)


@dataclass
class V121Ticket:
    key: ec.EllipticCurvePrivateKey
    encoded: bytes
    digest: bytes


@dataclass
class V121Key:
    key: ec.EllipticCurvePrivateKey
    digest: bytes | None = None  # of its own certificate, once it has one

    @classmethod
    def generate(cls) -> V121Key:
        return cls(ec.generate_private_key(ec.SECP256R1()))

    def issue(self, subject: V121Key, key_form: EccPointType = EccPointType.COMPRESSED_LSB_Y_0,
              r_form: EccPointType = EccPointType.X_COORDINATE_ONLY, its_aids=(PSID_CAM, PSID_DENM),
              subject_type: int = SUBJECT_AUTHORIZATION_TICKET) -> V121Ticket:
        """A certificate for subject's key signed by this key (self-signed when subject is self)."""
        signer = bytes([SignerInfoType.SELF]) if subject is self else \
            bytes([SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256]) + self.digest
        attributes = bytes([SubjectAttributeType.VERIFICATION_KEY, PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256]) + \
            public_point(subject.key.public_key(), key_form) + \
            bytes([SubjectAttributeType.ASSURANCE_LEVEL]) + ASSURANCE_LEVEL + \
            bytes([SubjectAttributeType.ITS_AID_SSP_LIST]) + var(b"".join(
                encode_length(aid) + var(b"\x01\x00\x00") for aid in its_aids))
        validity = bytes([ValidityRestrictionType.TIME_START_AND_END]) + \
            VALID_FROM_S.to_bytes(4, "big") + VALID_UNTIL_S.to_bytes(4, "big")
        signed = bytes([CERTIFICATE_VERSION]) + signer + bytes([subject_type]) + var(b"") + var(attributes) + \
            var(validity)
        encoded = signed + signature(self.key, signed, r_form)
        subject.digest = canonical_digest(encoded, len(signed))
        return V121Ticket(subject.key, encoded, subject.digest)


def secure(gn_packet: bytes, ticket: V121Ticket, signer: Signer, generation_time_us: int, psid: int = PSID_CAM,
           r_form: EccPointType = EccPointType.X_COORDINATE_ONLY, chain: tuple[bytes, ...] = (),
           payload_type: PayloadType = PayloadType.SIGNED) -> bytes:
    """gn_packet (unsecured) with its common header onwards as the signed payload of a v1.2.1 SecuredMessage."""
    if signer is Signer.DIGEST:
        signer_info = bytes([signer.value]) + ticket.digest
    elif signer is Signer.CERTIFICATE:
        signer_info = bytes([signer.value]) + ticket.encoded
    else:
        signer_info = bytes([signer.value]) + var(b"".join(chain) + ticket.encoded)
    headers = bytes([HeaderFieldType.SIGNER_INFO]) + signer_info + \
        bytes([HeaderFieldType.GENERATION_TIME]) + generation_time_us.to_bytes(8, "big") + \
        bytes([HeaderFieldType.ITS_AID]) + encode_length(psid)
    body = bytes([PROTOCOL_VERSION]) + var(headers) + bytes([payload_type]) + var(gn_packet[BASIC_HEADER_SIZE:])
    trailer_field_type = bytes([TrailerFieldType.SIGNATURE])
    trailer_signature = signature(ticket.key, b"", r_form)  # only its size matters here: the same for any key
    signed = body + encode_length(len(trailer_field_type) + len(trailer_signature)) + trailer_field_type
    message = signed + signature(ticket.key, signed, r_form)
    return with_basic_next_header(gn_packet, BasicNextHeader.SECURED_PACKET, message)
