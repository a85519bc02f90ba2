"""A secured packet of ETSI TS 103 097 v1.2.1 (clause 5), as the GN basic header's next header 2 carries it.

    message = parse_secured_message(packet[BASIC_HEADER_SIZE:])    # V2xDecodeError when malformed
    message.payload                      # the GN common header onwards (signed or unsecured payload)
    message.signed_bytes                 # what the signature covers

SecuredMessage = protocol_version (2) | header_fields<var> | payload | trailer_fields<var>. The signature covers
(clause 5.6) the encoding of every field before it, lengths included: protocol version, the header fields, the
payload, the length of the trailer fields, the trailer fields before the signature and the signature's type octet.
On the wire that is one span: from the protocol version up to and including the signature trailer field's type.
Header fields used: generation_time (Time64, TAI microseconds since 2004; or with its standard deviation),
expiration (Time32), generation_location, its_aid (the PSID), signer_info (a certificate, a certificate chain whose
last element is the signer's, or a HashedId8); the others are read past.
"""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.envelope import GenerationLocation
from coopdrive.v2x.security.v121_certificate import V121Certificate, V121Signature, read_certificate, read_signature
from coopdrive.v2x.security.v121_reader import (
    HASHED_ID8_SIZE, NONCE_SIZE, PROTOCOL_VERSION, HeaderFieldType, PayloadType, PresentationReader, SignerInfoType,
    SymmetricAlgorithm, TrailerFieldType, malformed)
from coopdrive.v2x.timebase import US_PER_S

_TIME64_SIZE, _TIME32_SIZE, _STANDARD_DEVIATION_SIZE = 8, 4, 1
_LATITUDE_SIZE = _LONGITUDE_SIZE = 4
# Elevation (clause 4.2.18) is kept as its raw 2 octets' value.
_ELEVATION_SIZE = 2
_PAYLOAD_TYPES_WITH_DATA = (PayloadType.UNSECURED, PayloadType.SIGNED, PayloadType.ENCRYPTED,
                            PayloadType.SIGNED_AND_ENCRYPTED)
_READABLE_PAYLOADS = (PayloadType.UNSECURED, PayloadType.SIGNED)
# "certificate" and "digest" as in the v1.3.1 results; a chain is named apart.
SIGNER_NAMES = {SignerInfoType.CERTIFICATE: "certificate", SignerInfoType.CERTIFICATE_CHAIN: "certificate_chain",
                SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256: "digest"}


def is_v121(envelope: bytes) -> bool:
    """Whether the bytes after a secured basic header are a v1.2.1 SecuredMessage (its first octet, the protocol
    version, is 2; v1.3.1's EtsiTs103097Data starts with 3)."""
    return len(envelope) > 0 and envelope[0] == PROTOCOL_VERSION


@dataclass(frozen=True, slots=True)
class V121Message:
    signer_type: int | None
    # The signer's HashedId8 (a digest signer's as sent, a certificate's as computed).
    signer_digest: bytes | None
    certificate: V121Certificate | None
    chain: tuple[V121Certificate, ...]
    psid: int | None
    generation_time_us: int | None
    expiry_time_us: int | None
    location: GenerationLocation | None
    payload_type: int
    payload: bytes
    signature: V121Signature | None
    signed_bytes: bytes

    @property
    def signer(self) -> str | None:
        return SIGNER_NAMES.get(self.signer_type)


@dataclass
class _Headers:
    signer_type: int | None = None
    signer_digest: bytes | None = None
    certificates: tuple[V121Certificate, ...] = ()
    psid: int | None = None
    generation_time_us: int | None = None
    expiry_time_us: int | None = None
    location: GenerationLocation | None = None


def _read_signer(reader: PresentationReader, headers: _Headers) -> None:
    kind = reader.u8()
    headers.signer_type = kind
    if kind == SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256:
        headers.signer_digest = reader.fixed(HASHED_ID8_SIZE)
    elif kind == SignerInfoType.CERTIFICATE:
        headers.certificates = (read_certificate(reader),)
    elif kind == SignerInfoType.CERTIFICATE_CHAIN:
        chain = reader.var_reader()
        certificates = []
        while not chain.at_end:
            certificates.append(read_certificate(chain))
        if not certificates:
            raise malformed("empty certificate chain")
        headers.certificates = tuple(certificates)
    elif kind == SignerInfoType.CERTIFICATE_DIGEST_WITH_OTHER_ALGORITHM:
        reader.u8()
        headers.signer_digest = reader.fixed(HASHED_ID8_SIZE)
    elif kind != SignerInfoType.SELF:
        reader.var_opaque()
    if headers.certificates:
        headers.signer_digest = headers.certificates[-1].digest


def _read_header_field(reader: PresentationReader, headers: _Headers) -> None:
    kind = reader.u8()
    if kind == HeaderFieldType.GENERATION_TIME:
        headers.generation_time_us = reader.uint(_TIME64_SIZE)
    elif kind == HeaderFieldType.GENERATION_TIME_STANDARD_DEVIATION:
        headers.generation_time_us = reader.uint(_TIME64_SIZE)
        reader.fixed(_STANDARD_DEVIATION_SIZE)
    elif kind == HeaderFieldType.EXPIRATION:
        headers.expiry_time_us = reader.uint(_TIME32_SIZE) * US_PER_S
    elif kind == HeaderFieldType.GENERATION_LOCATION:
        headers.location = GenerationLocation(reader.sint(_LATITUDE_SIZE), reader.sint(_LONGITUDE_SIZE),
                                              reader.uint(_ELEVATION_SIZE))
    elif kind == HeaderFieldType.ITS_AID:
        headers.psid = reader.length()
    elif kind == HeaderFieldType.SIGNER_INFO:
        if headers.signer_type is not None:
            raise malformed("two signer_info header fields")
        _read_signer(reader, headers)
    elif kind == HeaderFieldType.ENCRYPTION_PARAMETERS:
        if reader.u8() == SymmetricAlgorithm.AES_128_CCM:
            reader.fixed(NONCE_SIZE)
        else:
            reader.var_opaque()
    else:  # request_unrecognized_certificate and recipient_info are vectors too, as is any unknown field
        reader.var_opaque()


def _read_trailer(message: PresentationReader) -> tuple[V121Signature | None, int]:
    """The first signature trailer field and where the signed bytes end (after its type octet)."""
    trailer = message.var_reader()
    signature, signed_end = None, trailer.end
    while not trailer.at_end:
        kind = trailer.u8()
        if kind == TrailerFieldType.SIGNATURE and signature is None:
            signed_end = trailer.offset
            signature = read_signature(trailer)
        elif kind == TrailerFieldType.SIGNATURE:
            read_signature(trailer)
        else:
            trailer.var_opaque()
    return signature, signed_end


def parse_secured_message(envelope: bytes) -> V121Message:
    """Read every field; raises V2xDecodeError (malformed_security_envelope, unsupported_secured_content), nothing
    else, whatever the bytes."""
    envelope = bytes(envelope)
    message = PresentationReader(envelope)
    version = message.u8()
    if version != PROTOCOL_VERSION:
        raise malformed(f"protocol version {version}")
    headers = _Headers()
    fields = message.var_reader()
    while not fields.at_end:
        _read_header_field(fields, headers)
    payload_type = message.u8()
    if payload_type not in _PAYLOAD_TYPES_WITH_DATA and payload_type != PayloadType.SIGNED_EXTERNAL:
        raise malformed(f"payload type {payload_type}")
    payload = message.var_opaque() if payload_type in _PAYLOAD_TYPES_WITH_DATA else b""
    signature, signed_end = _read_trailer(message)
    if not message.at_end:
        raise malformed(f"{message.end - message.offset} octets after the trailer fields")
    if payload_type not in _READABLE_PAYLOADS:
        raise V2xDecodeError(RejectReason.UNSUPPORTED_SECURED_CONTENT, f"v1.2.1 payload type {payload_type}")
    certificate = headers.certificates[-1] if headers.certificates else None
    return V121Message(headers.signer_type, headers.signer_digest, certificate, headers.certificates, headers.psid,
                       headers.generation_time_us, headers.expiry_time_us, headers.location, payload_type, payload,
                       signature, envelope[:signed_end])
