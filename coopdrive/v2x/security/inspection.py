"""What a received packet's security envelope says: the one result that decode, the service and its statistics use.

    inspector = PacketInspector(store)                       # store: trusted roots (maybe none), ticket cache
    inspected = inspector.inspect(gn_packet, now_tai_us)     # now_tai_us None: freshness not judged
    inspected.unsecured_packet                               # GN packet without the envelope (None: unreadable)
    inspected.security                                       # SecurityResult, below
    reason = mode_drop_reason(mode, inspected.security)      # what a security mode drops (None: deliver)

Every secured packet is unwrapped and, whenever the signer's key is known, its signature checked, whatever the
mode; three separate questions are answered:
- `verified`: True the signature is valid for the signer's certificate (sent in full, or heard in full earlier
  from any station, found by HashedId8) and the PSID fits the BTP port; False an invalid signature, an envelope
  that cannot be read, or a PSID for another service; None unsigned, or the signer's certificate never heard
  (reason unknown_signer_digest).
- `fresh`: generation time within [now - 2 s, now + 0.5 s] of the packet's own clock source (the service clock
  live, the capture time in decode); None when not judged (no clock given, unsigned, not verified).
- `trusted`: True the certificate chains to a configured root (every link valid at generation time, signed by
  its issuer, the PSID permitted, the sender inside its region); False roots are configured and the chain fails
  (reason unknown_issuer, untrusted_root, certificate_expired, psid_not_permitted, ...); None when no root is
  configured (nothing to trust against), the packet is unsigned, or the signer is unknown.
`reason` is the first thing wrong or unknown, in that order (verified, fresh, trusted); None when nothing was.
A certificate whose packet signature verified is cached (bounded) so later digest-signed packets resolve.
"""

from __future__ import annotations

from coopdrive.v2x.geonet import (
    BASIC_HEADER_SIZE, BasicNextHeader, is_secured, parse_basic_header, with_basic_next_header)
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.certificate import Certificate, CertificateError
from coopdrive.v2x.security.crypto import data_digest, verify_digest
from coopdrive.v2x.security.envelope import SIGNER_SELF, SignedEnvelope, parse_signed_data
from coopdrive.v2x.security.profile import MAX_CLOCK_AHEAD_S, MAX_MESSAGE_AGE_S, PSID_OF_PORT, SecurityMode
from coopdrive.v2x.security.result import (
    UNSIGNED, InspectedPacket, SecurityResult, freshness_reason, sender_position)
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.v121_inspection import V121Inspector
from coopdrive.v2x.security.v121_message import is_v121
from coopdrive.v2x.timebase import US_PER_S


# A valid signature whose certificate chains to no configured root: verify_required drops it as `untrusted`
# (the certificate's own faults, expired or outside its region, keep their reasons).
_UNROOTED_CHAIN = frozenset({None, RejectReason.UNKNOWN_ISSUER, RejectReason.UNTRUSTED_ROOT,
                             RejectReason.UNKNOWN_ISSUER.value, RejectReason.UNTRUSTED_ROOT.value})


def mode_drop_reason(mode: SecurityMode, security: SecurityResult) -> RejectReason | None:
    """Why `mode` drops the packet, None to deliver it: off / sign_only drop nothing; sign_and_verify drops
    invalid signatures and stale or future packets; verify_required also drops unsigned packets, unknown
    signers and whatever is not trusted."""
    if not mode.verifies:
        return None
    if security.verified is False or security.fresh is False:
        return security.reason
    if not mode.drops_failures:
        return None
    if not security.signed:
        return RejectReason.UNSECURED_PACKET_REFUSED
    if security.verified is None or security.trusted is not True:
        chain_unrooted = security.reason in _UNROOTED_CHAIN
        return RejectReason.UNTRUSTED if security.verified and chain_unrooted else security.reason or RejectReason.UNTRUSTED
    return None


class PacketInspector:
    def __init__(self, store: CertificateStore, max_age_s: float = MAX_MESSAGE_AGE_S,
                 max_ahead_s: float = MAX_CLOCK_AHEAD_S):
        self.store = store
        self.max_age_us = round(max_age_s * US_PER_S)
        self.max_ahead_us = round(max_ahead_s * US_PER_S)
        # TS 103 097 v1.2.1 packets (GN version 0 roadside units), with their own store of signers heard.
        self.v121 = V121Inspector(store, max_age_s, max_ahead_s)

    def inspect(self, packet: bytes, now_tai_us: int | None = None) -> InspectedPacket:
        """Never raises: whatever the bytes, a result (unreadable envelopes are verified=False with the reason)."""
        packet = bytes(packet)
        if not is_secured(packet):
            return InspectedPacket(UNSIGNED, packet)
        try:
            parse_basic_header(packet)
            if is_v121(packet[BASIC_HEADER_SIZE:]):
                return self.v121.inspect(packet, now_tai_us)
            envelope = parse_signed_data(packet[BASIC_HEADER_SIZE:])
        except V2xDecodeError as error:
            return InspectedPacket(SecurityResult(True, verified=False, reason=error.reason), None)
        unsecured = with_basic_next_header(packet, BasicNextHeader.COMMON_HEADER, envelope.unsecured)
        return InspectedPacket(self._judge(envelope, unsecured, now_tai_us), unsecured)

    def _judge(self, envelope: SignedEnvelope, unsecured: bytes, now_tai_us: int | None) -> SecurityResult:
        kind, _ = envelope.signer
        if kind == SIGNER_SELF:
            # No key to check it with: delivered where the mode delivers what is not verified (off, sign_only).
            return SecurityResult(True, kind, None, None, reason=RejectReason.UNSUPPORTED_SIGNER, psid=envelope.psid,
                                  generation_time_us=envelope.generation_time_us)
        try:
            certificate, digest = self._certificate(envelope)
        except CertificateError as error:
            return SecurityResult(True, kind, None, False, reason=error.reason, psid=envelope.psid,
                                  generation_time_us=envelope.generation_time_us)
        base = {"signed": True, "signer": kind, "signer_digest": digest, "psid": envelope.psid,
                "generation_time_us": envelope.generation_time_us}
        if certificate is None:
            return SecurityResult(**base, reason=RejectReason.UNKNOWN_SIGNER_DIGEST)
        position = sender_position(envelope.location, unsecured)
        verified_reason = self._signature_reason(envelope, certificate, position[0])
        if verified_reason is not None:
            return SecurityResult(**base, verified=False, reason=verified_reason)
        if kind == "certificate":
            self.store.remember(certificate)
        fresh_reason = self._freshness_reason(envelope, now_tai_us)
        trusted, trust_reason = self._trust(envelope, certificate, position[1])
        return SecurityResult(**base, verified=True, fresh=None if now_tai_us is None else fresh_reason is None,
                              trusted=trusted, reason=fresh_reason or trust_reason)

    def _certificate(self, envelope: SignedEnvelope) -> tuple[Certificate | None, bytes]:
        kind, signer = envelope.signer
        if kind != "certificate":
            return self.store.resolve(signer), signer
        certificate = self.store.sent_in_full(envelope.certificate_bytes, signer[0])
        return certificate, certificate.digest

    @staticmethod
    def _signature_reason(envelope: SignedEnvelope, certificate: Certificate, port: int | None) -> RejectReason | None:
        expected_psid = PSID_OF_PORT.get(port) if port is not None else None
        if expected_psid is not None and envelope.psid != expected_psid:
            return RejectReason.PSID_PORT_MISMATCH
        if not verify_digest(certificate.public_key, envelope.signature,
                             data_digest(envelope.tbs_bytes, certificate.canonical)):
            return RejectReason.INVALID_SIGNATURE
        return None

    def _freshness_reason(self, envelope: SignedEnvelope, now_tai_us: int | None) -> RejectReason | None:
        return freshness_reason(envelope, now_tai_us, self.max_age_us, self.max_ahead_us)

    def _trust(self, envelope: SignedEnvelope, certificate: Certificate,
               position: tuple[int, int] | None) -> tuple[bool | None, RejectReason | None]:
        if not self.store.has_trusted_roots:
            return None, None
        if envelope.generation_time_us is None:
            return False, RejectReason.MISSING_GENERATION_TIME
        if envelope.psid not in certificate.app_psids:
            return False, RejectReason.PSID_NOT_PERMITTED
        latitude, longitude = position if position is not None else (None, None)
        try:
            self.store.check_chain(certificate, envelope.generation_time_us / US_PER_S, latitude, longitude)
        except CertificateError as error:
            return False, error.reason
        return True, None
