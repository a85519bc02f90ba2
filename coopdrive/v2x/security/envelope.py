"""Build the EtsiTs103097Data of a signed GeoNetworking packet, and read its parts back.

The envelope follows the 4-byte basic header (next header 2). In canonical OER the to-be-signed data starts
at byte 3 of it: protocolVersion (1 byte), the content choice tag (1 byte), hashId (1 byte, SignedData has
neither optional fields nor an extension marker), then tbsData.
"""

from __future__ import annotations

from dataclasses import dataclass

from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security import asn
from coopdrive.v2x.security.certificate import Certificate
from coopdrive.v2x.security.crypto import data_digest, sign_digest
from coopdrive.v2x.security.profile import SECURED_DATA_PROTOCOL_VERSION

TBS_OFFSET_IN_ENVELOPE = 3
# Choice tag + HashedId8; choice tag + SEQUENCE OF quantity (length byte, count byte) before the certificate.
SIGNER_DIGEST_SIZE = 1 + 8
SIGNER_CERTIFICATE_OVERHEAD = 3
# `self` (NULL): the choice tag alone.
SIGNER_SELF_SIZE = 1
# TS 103 097 v1.3.1 clause 5.2 allows a digest or a certificate as the signer of a message; another stack's
# "dummy" signing sends `self` with a zero signature, which carries a message but proves nothing.
SIGNER_SELF = "self"
CERTIFICATE_ENCODINGS_REMEMBERED = 1024
_CERTIFICATE_ENCODINGS: dict[bytes, bytes] = {}


@dataclass(frozen=True)
class GenerationLocation:
    """0.1 microdegree latitude / longitude, 0.1 m elevation (as HeaderInfo.generationLocation)."""

    latitude: int
    longitude: int
    elevation: int


def build_signed_data(unsecured: bytes, psid: int, generation_time_us: int, ticket: Certificate,
                      key: ec.EllipticCurvePrivateKey, full_certificate: bool,
                      location: GenerationLocation | None = None) -> bytes:
    header: dict = {"psid": psid, "generationTime": generation_time_us}
    if location is not None:
        header["generationLocation"] = {"latitude": location.latitude, "longitude": location.longitude,
                                        "elevation": location.elevation}
    tbs = {"payload": {"data": {"protocolVersion": SECURED_DATA_PROTOCOL_VERSION,
                                "content": ("unsecuredData", unsecured)}},
           "headerInfo": header}
    digest = data_digest(asn.encode(asn.TBS_DATA_TYPE, tbs), ticket.canonical)
    signer = ("certificate", [ticket.value]) if full_certificate else ("digest", ticket.digest)
    signed = {"hashId": "sha256", "tbsData": tbs, "signer": signer, "signature": sign_digest(key, digest)}
    return asn.encode(asn.DATA_TYPE, {"protocolVersion": SECURED_DATA_PROTOCOL_VERSION,
                                      "content": ("signedData", signed)})


@dataclass(frozen=True)
class SignedEnvelope:
    signed: dict
    # Byte spans of the envelope as received: what was hashed, and the signer's certificate (None: digest, self).
    tbs_bytes: bytes
    certificate_bytes: bytes | None
    unsecured: bytes
    psid: int
    generation_time_us: int | None
    expiry_time_us: int | None
    location: GenerationLocation | None

    @property
    def signer(self) -> tuple[str, object]:
        return self.signed["signer"]

    @property
    def signature(self) -> tuple[str, dict]:
        return self.signed["signature"]


def _certificate_encoding(value: dict, envelope: bytes, end: int) -> bytes:
    """The canonical encoding of a received certificate, which must be the bytes ending at envelope[end].

    A station sends the same ticket every second, so encodings are remembered by the certificate's sSig. A
    remembered encoding is used only when it equals the received bytes; otherwise (another certificate with
    the same sSig, e.g. a forgery sent to poison the cache) the certificate is encoded afresh.
    """
    try:
        key = value["signature"][1]["sSig"]
        known = _CERTIFICATE_ENCODINGS.get(key)
        if known is not None and envelope[end - len(known):end] == known:
            return known
        encoded = asn.encode(asn.CERTIFICATE_TYPE, value, check_types=False)
    except Exception as error:  # noqa: BLE001 -- asn1tools raises many types on garbage
        raise V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, f"{type(error).__name__}: {error}") from None
    if len(_CERTIFICATE_ENCODINGS) >= CERTIFICATE_ENCODINGS_REMEMBERED:
        _CERTIFICATE_ENCODINGS.pop(next(iter(_CERTIFICATE_ENCODINGS)))
    _CERTIFICATE_ENCODINGS[key] = encoded
    return encoded


def _signer_span(envelope: bytes, signer: tuple[str, object], end_of_signer: int) -> tuple[int, bytes | None]:
    """(where tbsData ends, the certificate's bytes or None for a digest or `self` signer)."""
    signer_kind, value = signer
    if signer_kind == "digest":
        return end_of_signer - SIGNER_DIGEST_SIZE, None
    if signer_kind == SIGNER_SELF:
        return end_of_signer - SIGNER_SELF_SIZE, None
    if signer_kind != "certificate" or len(value) != 1:
        raise V2xDecodeError(RejectReason.UNSUPPORTED_SIGNER, signer_kind)
    certificate = _certificate_encoding(value[0], envelope, end_of_signer)
    # SEQUENCE OF with one element: the choice tag, then quantity length (1) and quantity (1).
    start = end_of_signer - len(certificate)
    if envelope[start:end_of_signer] != certificate:
        raise V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, "signer certificate not canonical OER")
    return start - SIGNER_CERTIFICATE_OVERHEAD, certificate


def parse_signed_data(envelope: bytes) -> SignedEnvelope:
    """Decode and check the shape of a signed envelope; raises V2xDecodeError, never anything else.

    The spans are cut from the received bytes (the signature covers the bytes as sent): the envelope is
    header | tbsData | signer | signature, and the signature and the signer's certificate must re-encode to
    exactly their bytes at the end (so their sizes, and the certificate's HashedId8, are those sent). The
    to-be-signed part is not re-encoded as a whole: another stack's schema may know more extension additions
    (HeaderInfo of IEEE 1609.2-2022), whose canonical presence bitmap ours cannot reproduce.
    """
    try:
        value = asn.decode(asn.DATA_TYPE, envelope)
        kind, signed = value["content"]
        signature = asn.encode("Signature", signed["signature"], check_types=False) \
            if kind == "signedData" else b""
    except Exception as error:  # noqa: BLE001 -- asn1tools raises many types on garbage input
        raise V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, f"{type(error).__name__}: {error}") from None
    if value["protocolVersion"] != SECURED_DATA_PROTOCOL_VERSION:
        raise V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, f"protocolVersion {value['protocolVersion']}")
    if kind != "signedData":
        raise V2xDecodeError(RejectReason.UNSUPPORTED_SECURED_CONTENT, kind)
    if not envelope.endswith(signature):
        raise V2xDecodeError(RejectReason.MALFORMED_SECURITY_ENVELOPE, "signature not canonical OER (or trailing bytes)")
    if signed["hashId"] != "sha256":
        raise V2xDecodeError(RejectReason.UNSUPPORTED_HASH_ALGORITHM, str(signed["hashId"]))
    tbs = signed["tbsData"]
    data = tbs["payload"].get("data")
    if data is None or data["protocolVersion"] != SECURED_DATA_PROTOCOL_VERSION or \
            data["content"][0] != "unsecuredData":
        raise V2xDecodeError(RejectReason.UNSUPPORTED_SECURED_CONTENT, "payload is not unsecured data")
    end_of_tbs, certificate_bytes = _signer_span(envelope, signed["signer"], len(envelope) - len(signature))
    header = tbs["headerInfo"]
    location = header.get("generationLocation")
    return SignedEnvelope(
        signed, envelope[TBS_OFFSET_IN_ENVELOPE:end_of_tbs], certificate_bytes, data["content"][1], header["psid"],
        header.get("generationTime"), header.get("expiryTime"),
        GenerationLocation(location["latitude"], location["longitude"], location["elevation"]) if location else None)
