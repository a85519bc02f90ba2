"""Verify received secured GeoNetworking packets (TS 103 097 v1.3.1 signed data) and unwrap them.

    verifier = SecurityVerifier(store)
    ok, reason, signer_digest = verifier.verify(packet, now_tai_us)
    opened = verifier.open(packet, now_tai_us)   # also the unsecured packet, for the ordinary decode path

Every rejection is counted in `rejected_by_reason`; nothing but a result comes out, whatever the bytes.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import NamedTuple

from coopdrive.v2x.btp import parse_btp_b
from coopdrive.v2x.geonet import (
    BASIC_HEADER_SIZE, SUPPORTED_GN_VERSIONS, BasicNextHeader, CommonNextHeader, GnPacket, parse_basic_header, parse_gn,
    with_basic_next_header)
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.certificate import Certificate, CertificateError
from coopdrive.v2x.security.crypto import data_digest, verify_digest
from coopdrive.v2x.security.envelope import SIGNER_SELF, SignedEnvelope, parse_signed_data
from coopdrive.v2x.security.profile import MAX_CLOCK_AHEAD_S, MAX_MESSAGE_AGE_S, PSID_OF_PORT
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.v121_message import is_v121, parse_secured_message
from coopdrive.v2x.timebase import US_PER_S


class VerificationResult(NamedTuple):
    ok: bool
    reason: RejectReason | None
    # HashedId8 of the signer's ticket when the envelope could be read that far.
    signer_digest: bytes | None


@dataclass(frozen=True)
class OpenedPacket:
    result: VerificationResult
    # The same GN packet without the envelope (basic next header = common header), None when unreadable.
    unsecured_packet: bytes | None = None
    psid: int | None = None
    generation_time_us: int | None = None
    # True when the signer was sent as a full certificate, False for a digest.
    full_certificate: bool | None = None
    # False when only unwrapped (no signature, chain or time checked).
    verified: bool = False


class _Rejected(Exception):
    def __init__(self, reason: RejectReason, signer_digest: bytes | None):
        super().__init__(reason.value)
        self.reason, self.signer_digest = reason, signer_digest


class SecurityVerifier:
    def __init__(self, store: CertificateStore, max_age_s: float = MAX_MESSAGE_AGE_S,
                 max_ahead_s: float = MAX_CLOCK_AHEAD_S,
                 accepted_gn_versions: tuple[int, ...] = SUPPORTED_GN_VERSIONS):
        self.store = store
        self.max_age_us = round(max_age_s * US_PER_S)
        self.max_ahead_us = round(max_ahead_s * US_PER_S)
        self.accepted_gn_versions = accepted_gn_versions
        self.verified_count = 0
        self.rejected_by_reason: Counter[RejectReason] = Counter()

    def verify(self, packet: bytes, now_tai_us: int) -> VerificationResult:
        return self.open(packet, now_tai_us).result

    def open(self, packet: bytes, now_tai_us: int) -> OpenedPacket:
        """Verify and unwrap; a failure is counted and returned, never raised."""
        return self._guarded(packet, now_tai_us, verify=True)

    def unwrap(self, packet: bytes, count: bool = True) -> OpenedPacket:
        """Read the envelope without checking signature, chain or time (security modes off / sign_only)."""
        return self._guarded(packet, 0, verify=False, count=count)

    def _guarded(self, packet: bytes, now_tai_us: int, verify: bool, count: bool = True) -> OpenedPacket:
        try:
            opened = self._open(bytes(packet), now_tai_us, verify)
        except _Rejected as rejected:
            if count:
                self.rejected_by_reason[rejected.reason] += 1
            return OpenedPacket(VerificationResult(False, rejected.reason, rejected.signer_digest))
        if verify:
            self.verified_count += 1
        return opened

    def _open(self, packet: bytes, now_tai_us: int, verify: bool) -> OpenedPacket:
        try:
            basic = parse_basic_header(packet, self.accepted_gn_versions)
        except V2xDecodeError as error:
            raise _Rejected(error.reason, None) from None
        if basic.next_header != BasicNextHeader.SECURED_PACKET:
            raise _Rejected(RejectReason.UNSECURED_PACKET_REFUSED, None)
        if is_v121(packet[BASIC_HEADER_SIZE:]):
            return _unwrap_v121(packet, verify)
        try:
            envelope = parse_signed_data(packet[BASIC_HEADER_SIZE:])
        except V2xDecodeError as error:
            raise _Rejected(error.reason, None) from None
        signer_kind, signer = envelope.signer
        certificate, digest = self._signer(envelope, verify)
        unsecured = with_basic_next_header(packet, BasicNextHeader.COMMON_HEADER, envelope.unsecured)
        gn = self._check_psid_against_port(unsecured, envelope.psid, digest)
        if verify:
            self._check_time(envelope, now_tai_us, digest)
            self._check_signer(envelope, certificate, gn, signer_kind == "certificate")
        return OpenedPacket(VerificationResult(True, None, digest), unsecured, envelope.psid,
                            envelope.generation_time_us, signer_kind == "certificate", verify)

    def _signer(self, envelope: SignedEnvelope, verify: bool) -> tuple[Certificate | None, bytes]:
        kind, signer = envelope.signer
        if kind == "certificate":
            try:
                certificate = self.store.sent_in_full(envelope.certificate_bytes, signer[0])
            except CertificateError as error:
                raise _Rejected(error.reason, None) from None
            return certificate, certificate.digest
        if kind == SIGNER_SELF:
            if verify:
                raise _Rejected(RejectReason.UNSUPPORTED_SIGNER, None)
            return None, None
        certificate = self.store.resolve(signer)
        if certificate is None and verify:
            raise _Rejected(RejectReason.UNKNOWN_SIGNER_DIGEST, signer)
        return certificate, signer

    def _check_psid_against_port(self, unsecured: bytes, psid: int, digest: bytes) -> GnPacket:
        try:
            gn = parse_gn(unsecured, self.accepted_gn_versions)
            if gn.common.next_header != CommonNextHeader.BTP_B:
                raise V2xDecodeError(RejectReason.NOT_BTP_B)
            btp, _ = parse_btp_b(gn.payload)
        except V2xDecodeError as error:
            raise _Rejected(error.reason, digest) from None
        expected = PSID_OF_PORT.get(btp.destination_port)
        if expected is None:
            raise _Rejected(RejectReason.UNKNOWN_BTP_PORT, digest)
        if psid != expected:
            raise _Rejected(RejectReason.PSID_PORT_MISMATCH, digest)
        return gn

    def _check_time(self, envelope: SignedEnvelope, now_tai_us: int, digest: bytes) -> None:
        generated = envelope.generation_time_us
        if generated is None:
            raise _Rejected(RejectReason.MISSING_GENERATION_TIME, digest)
        if generated > now_tai_us + self.max_ahead_us:
            raise _Rejected(RejectReason.FUTURE_GENERATION_TIME, digest)
        expiry = envelope.expiry_time_us
        if now_tai_us - generated > self.max_age_us or (expiry is not None and now_tai_us > expiry):
            raise _Rejected(RejectReason.STALE_GENERATION_TIME, digest)

    def _check_signer(self, envelope: SignedEnvelope, certificate: Certificate, gn: GnPacket,
                      heard_in_full: bool) -> None:
        digest = certificate.digest
        if envelope.psid not in certificate.app_psids:
            raise _Rejected(RejectReason.PSID_NOT_PERMITTED, digest)
        if envelope.location is not None:
            latitude, longitude = envelope.location.latitude, envelope.location.longitude
        else:
            position = gn.extended.source_position
            latitude, longitude = position.latitude_tenth_microdeg, position.longitude_tenth_microdeg
        try:
            self.store.check_chain(certificate, envelope.generation_time_us / US_PER_S, latitude, longitude)
        except CertificateError as error:
            raise _Rejected(error.reason, digest) from None
        if heard_in_full:
            self.store.remember(certificate)
        if not verify_digest(certificate.public_key, envelope.signature,
                             data_digest(envelope.tbs_bytes, certificate.canonical)):
            raise _Rejected(RejectReason.INVALID_SIGNATURE, digest)


def _unwrap_v121(packet: bytes, verify: bool) -> OpenedPacket:
    """A TS 103 097 v1.2.1 packet unwrapped (to read its sender); its signature is judged by inspection.py only."""
    if verify:
        raise _Rejected(RejectReason.UNSUPPORTED_SECURED_CONTENT, None)
    try:
        message = parse_secured_message(packet[BASIC_HEADER_SIZE:])
    except V2xDecodeError as error:
        raise _Rejected(error.reason, None) from None
    unsecured = with_basic_next_header(packet, BasicNextHeader.COMMON_HEADER, message.payload)
    return OpenedPacket(VerificationResult(True, None, message.signer_digest), unsecured, message.psid,
                        message.generation_time_us, message.certificate is not None, False)
