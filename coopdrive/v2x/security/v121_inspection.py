"""Judge a TS 103 097 v1.2.1 secured packet into the SecurityResult a v1.3.1 one gets (inspection.py's contract).

    inspector = V121Inspector(store)                      # store: only asked whether roots are configured
    inspected = inspector.inspect(gn_packet, now_tai_us)  # InspectedPacket, never raises

- `verified`: True the ECDSA signature is valid for the signer's certificate (sent in the packet, alone or as the
  last of a chain, or heard in full earlier: a small bounded store by HashedId8) and the ITS-AID fits the BTP port;
  False an invalid signature, an unreadable message, a signer or algorithm we cannot use; None the signer's digest
  names a certificate never heard (reason unknown_signer_digest).
- `fresh`: as for v1.3.1 (generation_time header field, expiration).
- `trusted`: v1.2.1 certificates cannot chain to the (v1.3.1) roots we are given: None when none are configured,
  else False with reason unknown_issuer (verify_required drops it as untrusted).
A message without a signature trailer field is unsigned (signed False), its payload delivered.
"""

from __future__ import annotations

from coopdrive.v2x.geonet import BASIC_HEADER_SIZE, BasicNextHeader, with_basic_next_header
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.profile import MAX_CLOCK_AHEAD_S, MAX_MESSAGE_AGE_S, PSID_OF_PORT
from coopdrive.v2x.security.result import (
    UNSIGNED, InspectedPacket, SecurityResult, freshness_reason, sender_position)
from coopdrive.v2x.security.store import DEFAULT_TICKET_CACHE_SIZE, CertificateStore
from coopdrive.v2x.security.v121_certificate import V121Certificate, verify_ecdsa
from coopdrive.v2x.security.v121_message import V121Message, parse_secured_message
from coopdrive.v2x.security.v121_reader import PublicKeyAlgorithm, SignerInfoType
from coopdrive.v2x.timebase import US_PER_S

_SIGNERS_WITH_CERTIFICATE = (SignerInfoType.CERTIFICATE, SignerInfoType.CERTIFICATE_CHAIN)


class V121Inspector:
    def __init__(self, store: CertificateStore, max_age_s: float = MAX_MESSAGE_AGE_S,
                 max_ahead_s: float = MAX_CLOCK_AHEAD_S, cache_size: int = DEFAULT_TICKET_CACHE_SIZE):
        self.store = store
        self.max_age_us = round(max_age_s * US_PER_S)
        self.max_ahead_us = round(max_ahead_s * US_PER_S)
        # Signers' certificates whose packet signature verified, by HashedId8: a store of their own, bounded as the
        # v1.3.1 one, so that a v1.3.1 digest never resolves to a v1.2.1 certificate.
        self.heard = CertificateStore(ticket_cache_size=cache_size)

    def inspect(self, packet: bytes, now_tai_us: int | None = None) -> InspectedPacket:
        try:
            message = parse_secured_message(packet[BASIC_HEADER_SIZE:])
        except V2xDecodeError as error:
            return InspectedPacket(SecurityResult(True, verified=False, reason=error.reason), None)
        unsecured = with_basic_next_header(packet, BasicNextHeader.COMMON_HEADER, message.payload)
        if message.signature is None:
            return InspectedPacket(UNSIGNED, unsecured)
        return InspectedPacket(self._judge(message, unsecured, now_tai_us), unsecured)

    def _judge(self, message: V121Message, unsecured: bytes, now_tai_us: int | None) -> SecurityResult:
        base = {"signed": True, "signer": message.signer, "signer_digest": message.signer_digest,
                "psid": message.psid, "generation_time_us": message.generation_time_us}
        if message.signer_type not in (*_SIGNERS_WITH_CERTIFICATE, SignerInfoType.CERTIFICATE_DIGEST_WITH_SHA256):
            return SecurityResult(**base, verified=False, reason=RejectReason.UNSUPPORTED_SIGNER)
        if message.signature.algorithm != PublicKeyAlgorithm.ECDSA_NISTP256_WITH_SHA256:
            return SecurityResult(**base, verified=False, reason=RejectReason.UNSUPPORTED_HASH_ALGORITHM)
        certificate = message.certificate or self.heard.resolve(message.signer_digest)
        if certificate is None:
            return SecurityResult(**base, reason=RejectReason.UNKNOWN_SIGNER_DIGEST)
        port, _ = sender_position(message.location, unsecured)
        verified_reason = _signature_reason(message, certificate, port)
        if verified_reason is not None:
            return SecurityResult(**base, verified=False, reason=verified_reason)
        if message.signer_type in _SIGNERS_WITH_CERTIFICATE:
            self.heard.remember(certificate)
        fresh_reason = freshness_reason(message, now_tai_us, self.max_age_us, self.max_ahead_us)
        trusted, trust_reason = (False, RejectReason.UNKNOWN_ISSUER) if self.store.has_trusted_roots else (None, None)
        return SecurityResult(**base, verified=True, fresh=None if now_tai_us is None else fresh_reason is None,
                              trusted=trusted, reason=fresh_reason or trust_reason)


def _signature_reason(message: V121Message, certificate: V121Certificate, port: int | None) -> RejectReason | None:
    expected_psid = PSID_OF_PORT.get(port) if port is not None else None
    if expected_psid is not None and message.psid != expected_psid:
        return RejectReason.PSID_PORT_MISMATCH
    try:
        key = certificate.public_key
    except ValueError:
        return RejectReason.INVALID_CERTIFICATE
    if not verify_ecdsa(key, message.signature, message.signed_bytes):
        return RejectReason.INVALID_SIGNATURE
    return None
