"""The one reading of the security layer's result: signed, verified, trusted and why, for delivered and refused
packets, and the sender read through a secured packet's envelope."""

from dataclasses import dataclass

import pytest

from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.layer import ModeSecurityLayer
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.security_verdict import (
    UNSIGNED, SecurityVerdict, Sender, sender_of, verdict_of_opened, verdict_of_refusal)

from .signed import cam_packet, now_tai_us


@pytest.fixture
def signed(p256_pki):
    signer = p256_pki.signer("a", 4101, bytes.fromhex("020000004101"))
    return signer.sign(cam_packet(signer), now_tai_us())


def layer(pki, mode: SecurityMode) -> ModeSecurityLayer:
    return ModeSecurityLayer(mode, SecurityVerifier(pki.store()), pki.signer("b") if mode.signs else None)


def test_a_packet_verified_against_our_root_is_signed_verified_and_trusted(p256_pki, signed):
    _, opened = layer(p256_pki, SecurityMode.VERIFY_REQUIRED).open(signed)
    assert verdict_of_opened(opened) == SecurityVerdict(True, True, True, None)


def test_a_sound_packet_delivered_in_mode_off_is_signed_and_nothing_is_held_against_it(p256_pki, signed):
    # Whether mode off checks what it can (branch v2xdec) or only unwraps, nothing failed.
    _, opened = layer(p256_pki, SecurityMode.OFF).open(signed)
    verdict = verdict_of_opened(opened)
    assert verdict.signed and verdict.verified is not False and verdict.trusted is not False
    assert verdict.reason is None


def test_an_unsigned_packet_has_the_unsigned_verdict():
    assert verdict_of_opened(None) == UNSIGNED and not UNSIGNED.signed


def test_a_result_that_answers_for_itself_is_read_as_it_is():
    @dataclass
    class Result:
        signed: bool
        verified: bool | None
        trusted: bool | None
        reason: RejectReason | None

    assert verdict_of_opened(Result(True, True, False, RejectReason.UNKNOWN_ISSUER)) == \
        SecurityVerdict(True, True, False, "unknown_issuer")


@pytest.mark.parametrize("reason, verified, trusted", [
    (RejectReason.INVALID_SIGNATURE, False, None), (RejectReason.UNKNOWN_ISSUER, None, False),
    (RejectReason.UNTRUSTED_ROOT, None, False), (RejectReason.CERTIFICATE_EXPIRED, None, False),
    (RejectReason.UNKNOWN_SIGNER_DIGEST, None, None), (RejectReason.STALE_GENERATION_TIME, None, None)])
def test_a_refusal_says_what_its_reason_tells(signed, reason, verified, trusted):
    assert verdict_of_refusal(signed, reason) == SecurityVerdict(True, verified, trusted, reason.value)


def test_the_sender_of_a_secured_packet_is_read_inside_its_envelope(p256_pki, signed):
    def unwrap(packet: bytes) -> bytes | None:
        return SecurityVerifier(p256_pki.store()).unwrap(packet, count=False).unsecured_packet

    assert sender_of(signed, unwrap) == Sender(bytes.fromhex("020000004101"), 4101)
    assert sender_of(signed) == sender_of(b"\x11") == Sender(None, None)
