import pytest

from coopdrive.v2x.packet import decode_packet
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.certificate import CircularArea, issue_certificate
from coopdrive.v2x.security.crypto import curve_of_key
from coopdrive.v2x.security.envelope import build_signed_data
from coopdrive.v2x.security.pki import create_untrusted_pki, issue_expired_ticket, tamper_packet
from coopdrive.v2x.security.profile import PSID_CAM, PSID_DENM
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import US_PER_S

from .signed import cam_packet, denm_packet, iclcm_packet, now_tai_us

SECOND_US = US_PER_S


def rejected(verifier, packet, now, reason):
    result = verifier.verify(packet, now)
    assert (result.ok, result.reason) == (False, reason)
    assert verifier.rejected_by_reason[reason] >= 1
    return result


def test_our_signed_cam_denm_and_iclcm_verify_and_decode_to_what_was_sent(pki):
    signer, verifier, now = pki.signer("a"), SecurityVerifier(pki.store()), now_tai_us()
    for make in (cam_packet, denm_packet, iclcm_packet):
        packet = make(signer)
        opened = verifier.open(signer.sign(packet, now), now)
        assert opened.result == (True, None, signer.identity.ticket.digest)
        assert opened.unsecured_packet == packet
        assert decode_packet(opened.unsecured_packet).station_id == signer.station_id
    assert curve_of_key(signer.identity.key).ec_curve().name == pki.root.public_key.curve.name
    assert verifier.verified_count == 3 and not verifier.rejected_by_reason


def test_a_digest_signer_resolves_after_a_packet_that_carried_the_full_certificate(pki):
    signer, verifier, now = pki.signer("a"), SecurityVerifier(pki.store()), now_tai_us()
    with_certificate = signer.sign(cam_packet(signer), now)
    with_digest = signer.sign(cam_packet(signer), now + SECOND_US // 10)
    assert len(with_digest) < len(with_certificate)
    result = rejected(verifier, with_digest, now, RejectReason.UNKNOWN_SIGNER_DIGEST)
    assert result.signer_digest == signer.identity.ticket.digest
    assert verifier.verify(with_certificate, now).ok
    assert verifier.verify(with_digest, now + SECOND_US // 10).ok


def test_an_expired_ticket_is_rejected_as_certificate_expired(p256_pki):
    signer = SecuredPacketSigner([issue_expired_ticket(p256_pki, "a")])
    now = now_tai_us()
    rejected(SecurityVerifier(p256_pki.store()), signer.sign(cam_packet(signer), now), now,
             RejectReason.CERTIFICATE_EXPIRED)


def test_a_ticket_under_a_root_nobody_trusts_is_rejected_as_untrusted_root(p256_pki, tmp_path):
    rogue = create_untrusted_pki(tmp_path / "rogue")
    # The rogue authority and root are known (say, from the capture), only the real root is trusted.
    store = p256_pki.store()
    store.add_authority(rogue.authority)
    store.add_authority(rogue.root)
    signer, now = rogue.signer("rogue"), now_tai_us()
    rejected(SecurityVerifier(store), signer.sign(cam_packet(signer), now), now, RejectReason.UNTRUSTED_ROOT)


def test_a_ticket_from_an_authority_never_heard_of_is_rejected_as_unknown_issuer(p256_pki, tmp_path):
    signer, now = create_untrusted_pki(tmp_path / "rogue").signer("rogue"), now_tai_us()
    rejected(SecurityVerifier(p256_pki.store()), signer.sign(cam_packet(signer), now), now,
             RejectReason.UNKNOWN_ISSUER)


def test_a_cam_signed_under_the_denm_psid_is_rejected_as_psid_port_mismatch(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    ticket, key = signer.identity.ticket, signer.identity.key
    packet = cam_packet(signer)
    envelope = build_signed_data(packet[4:], PSID_DENM, now, ticket, key, full_certificate=True)
    rejected(SecurityVerifier(p256_pki.store()), bytes([packet[0] & 0xF0 | 2]) + packet[1:4] + envelope, now,
             RejectReason.PSID_PORT_MISMATCH)


def test_a_ticket_without_the_denm_psid_cannot_sign_a_denm(p256_pki):
    signer = SecuredPacketSigner([p256_pki.issue_ticket("cam-only", psids=(PSID_CAM,))])
    now = now_tai_us()
    rejected(SecurityVerifier(p256_pki.store()), signer.sign(denm_packet(signer), now), now,
             RejectReason.PSID_NOT_PERMITTED)


def test_a_generation_time_older_than_two_seconds_is_stale_and_one_ahead_of_our_clock_is_refused(p256_pki):
    signer, verifier, now = p256_pki.signer("a"), SecurityVerifier(p256_pki.store()), now_tai_us()
    packet = signer.sign(cam_packet(signer), now)
    assert verifier.verify(packet, now + 2 * SECOND_US).ok
    rejected(verifier, packet, now + 2 * SECOND_US + 1, RejectReason.STALE_GENERATION_TIME)
    rejected(verifier, packet, now - SECOND_US, RejectReason.FUTURE_GENERATION_TIME)


def test_a_sender_outside_its_ticket_region_is_rejected(p256_pki):
    far_away = CircularArea(latitude_deg=48.1, longitude_deg=11.6, radius_m=10_000)
    around_here = CircularArea(latitude_deg=57.70, longitude_deg=11.97, radius_m=10_000)
    verifier, now = SecurityVerifier(p256_pki.store()), now_tai_us()
    for region, ok in ((around_here, True), (far_away, False)):
        signer = SecuredPacketSigner([p256_pki.issue_ticket("regional", region=region)])
        result = verifier.verify(signer.sign(cam_packet(signer), now), now)
        assert result.ok == ok and result.reason == (None if ok else RejectReason.OUTSIDE_CERTIFICATE_REGION)


def test_a_tampered_payload_fails_as_invalid_signature_though_its_envelope_still_reads(pki):
    signer, verifier, now = pki.signer("a"), SecurityVerifier(pki.store()), now_tai_us()
    tampered = tamper_packet(signer.sign(cam_packet(signer), now), bit_in_message=3)
    rejected(verifier, tampered, now, RejectReason.INVALID_SIGNATURE)
    assert verifier.unwrap(tampered).result.ok


def test_a_packet_from_a_ticket_signed_by_another_authority_key_fails_the_chain(p256_pki, tmp_path):
    rogue = create_untrusted_pki(tmp_path / "rogue")
    # A ticket naming the real authority as issuer but signed with the rogue authority's key.
    forged = p256_pki.issue_ticket("forged")
    ticket, key = forged
    fake = issue_certificate("forged", key.public_key(), rogue.authority_key, p256_pki.authority,
                             start_s=ticket.valid_from_s, duration_hours=24, app_psids=(PSID_CAM,))
    signer, now = SecuredPacketSigner([(fake, key)]), now_tai_us()
    rejected(SecurityVerifier(p256_pki.store()), signer.sign(cam_packet(signer), now), now,
             RejectReason.INVALID_CERTIFICATE_SIGNATURE)


def test_a_store_refuses_to_trust_a_root_whose_self_signature_is_wrong(p256_pki, tmp_path):
    rogue = create_untrusted_pki(tmp_path / "rogue")
    with pytest.raises(ValueError, match="invalid_certificate_signature"):
        CertificateStore(trusted_roots=[rogue.authority])
