import pytest

from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.security import asn
from coopdrive.v2x.security.layer import ModeSecurityLayer
from coopdrive.v2x.security.pki import tamper_packet
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import US_PER_S

from .signed import cam_packet, now_tai_us


def receiver(pki, mode, now):
    layer = ModeSecurityLayer(mode, SecurityVerifier(pki.store()), pki.signer("b"), clock_tai_us=lambda: now)
    return layer, V2xPacketCodec(security=layer)


def refused(codec, packet, reason):
    with pytest.raises(V2xDecodeError) as error:
        codec.decode_packet(packet)
    assert error.value.reason == reason


def test_without_a_security_layer_a_secured_packet_is_decoded_and_its_signature_checked_but_not_trusted(p256_pki):
    signer = p256_pki.signer("a")
    decoded = V2xPacketCodec().decode_packet(signer.sign(cam_packet(signer), now_tai_us()))
    assert decoded.station_id == signer.station_id
    assert (decoded.security.signed, decoded.security.verified, decoded.security.trusted) == (True, True, None)
    assert decoded.security.fresh is None  # no clock: not judged


def test_sign_and_verify_drops_a_tampered_or_stale_packet_but_delivers_an_unknown_signer(p256_pki):
    now = now_tai_us()
    layer, codec = receiver(p256_pki, SecurityMode.SIGN_AND_VERIFY, now)
    signer = p256_pki.signer("a")
    secured = signer.sign(cam_packet(signer), now)
    refused(codec, tamper_packet(secured), RejectReason.INVALID_SIGNATURE)
    refused(codec, signer.sign(cam_packet(signer), now - 10 * US_PER_S), RejectReason.STALE_GENERATION_TIME)
    signer.sign(cam_packet(signer), now + 1)  # full certificate, which the stranger below never hears
    stranger = receiver(p256_pki, SecurityMode.SIGN_AND_VERIFY, now)[1]
    assert stranger.decode_packet(signer.sign(cam_packet(signer), now + 2)).security.verified is None


def test_verify_required_delivers_verified_packets_and_drops_unsecured_and_tampered_ones(p256_pki):
    now = now_tai_us()
    layer, codec = receiver(p256_pki, SecurityMode.VERIFY_REQUIRED, now)
    signer = p256_pki.signer("a")
    secured = signer.sign(cam_packet(signer), now)
    decoded = codec.decode_packet(secured)
    assert decoded.station_id == signer.station_id and decoded.security.verified
    assert decoded.security.trusted and decoded.security.fresh
    assert decoded.security.signer_digest == signer.identity.ticket.digest
    refused(codec, cam_packet(signer), RejectReason.UNSECURED_PACKET_REFUSED)
    refused(codec, tamper_packet(secured), RejectReason.INVALID_SIGNATURE)
    assert layer.status["verified"] == 1 and layer.status["invalid_signature"] == 1


def test_sign_and_verify_delivers_an_unknown_signer_marked_unverified_and_counts_why(p256_pki):
    now = now_tai_us()
    layer, codec = receiver(p256_pki, SecurityMode.SIGN_AND_VERIFY, now)
    signer = p256_pki.signer("a")
    signer.sign(cam_packet(signer), now)
    digest_only = signer.sign(cam_packet(signer), now + 1)
    decoded = codec.decode_packet(digest_only)
    assert decoded.security.verified is None
    assert decoded.security.reason == RejectReason.UNKNOWN_SIGNER_DIGEST
    assert codec.decode_packet(cam_packet(signer)).security.signed is False
    assert layer.status == {"verified": 0, "delivered_unverified": 1, "unknown_signer_digest": 1}


def test_off_sends_unsigned_and_delivers_a_tampered_packet_marked_invalid(p256_pki):
    now = now_tai_us()
    layer = ModeSecurityLayer(SecurityMode.OFF, SecurityVerifier(p256_pki.store()), clock_tai_us=lambda: now)
    codec = V2xPacketCodec(security=layer)
    signer = p256_pki.signer("a")
    assert layer.seal(cam_packet(signer)) == cam_packet(signer)
    decoded = codec.decode_packet(tamper_packet(signer.sign(cam_packet(signer), now), bit_in_message=40))
    assert decoded.security.verified is False and decoded.station_id == signer.station_id


def test_a_station_heard_for_the_first_time_makes_our_next_packet_carry_the_full_certificate(p256_pki):
    now = now_tai_us()
    layer, codec = receiver(p256_pki, SecurityMode.SIGN_AND_VERIFY, now)
    ours = layer.signer
    layer.seal(cam_packet(ours))
    assert layer.signer.full_certificate_count == 1
    other = p256_pki.signer("a")
    codec.decode_packet(other.sign(cam_packet(other), now))
    layer.seal(cam_packet(ours), now + 1)
    codec.decode_packet(other.sign(cam_packet(other), now + 2))
    layer.seal(cam_packet(ours), now + 3)
    assert layer.signer.full_certificate_count == 2


def test_a_signing_mode_needs_a_signer(p256_pki):
    with pytest.raises(ValueError, match="sign_only needs a signer"):
        ModeSecurityLayer(SecurityMode.SIGN_ONLY, SecurityVerifier(p256_pki.store()))


def dummy_signed(packet: bytes) -> bytes:
    """`packet` re-signed as another stack's "dummy" signing does: signer `self`, a zero signature."""
    envelope = asn.decode(asn.DATA_TYPE, packet[BASIC_HEADER_SIZE:])
    signed = envelope["content"][1]
    signed["signer"] = ("self", None)
    signed["signature"] = ("ecdsaNistP256Signature", {"rSig": ("x-only", bytes(32)), "sSig": bytes(32)})
    return packet[:BASIC_HEADER_SIZE] + asn.encode(asn.DATA_TYPE, envelope)


def test_a_dummy_signed_packet_is_delivered_unverified_with_security_off_and_refused_where_verification_is_required(
        p256_pki):
    now = now_tai_us()
    signer = p256_pki.signer("a")
    packet = dummy_signed(signer.sign(cam_packet(signer), now))
    off = ModeSecurityLayer(SecurityMode.OFF, SecurityVerifier(p256_pki.store()), clock_tai_us=lambda: now)
    decoded = V2xPacketCodec(security=off).decode_packet(packet)
    assert decoded.station_id == signer.station_id
    assert (decoded.security.signer, decoded.security.verified, decoded.security.reason) == (
        "self", None, RejectReason.UNSUPPORTED_SIGNER)
    assert off.status["unsupported_signer"] == 1
    refused(receiver(p256_pki, SecurityMode.VERIFY_REQUIRED, now)[1], packet, RejectReason.UNSUPPORTED_SIGNER)


def test_the_verifier_refuses_a_dummy_signed_packet_as_an_unsupported_signer_and_unwraps_it_unchecked(p256_pki):
    signer = p256_pki.signer("a")
    packet = dummy_signed(signer.sign(cam_packet(signer), now_tai_us()))
    verifier = SecurityVerifier(p256_pki.store())
    assert verifier.verify(packet, now_tai_us()).reason == RejectReason.UNSUPPORTED_SIGNER
    assert V2xPacketCodec().decode_packet(verifier.unwrap(packet).unsecured_packet).station_id == signer.station_id
