import pytest

from coopdrive.v2x.security.envelope import parse_signed_data
from coopdrive.v2x.security.profile import PSID_CAM, PSID_DENM, PSID_ICLCM
from coopdrive.v2x.security.signer import PseudonymChangeRefused, SecuredPacketSigner
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import US_PER_S

from .signed import cam_packet, denm_packet, iclcm_packet, now_tai_us

CAM_PERIOD_US = US_PER_S // 10


def signer_kind(secured: bytes) -> str:
    return parse_signed_data(secured[4:]).signer[0]


def test_cams_carry_the_full_certificate_once_per_second_and_the_digest_otherwise(p256_pki):
    signer, start = p256_pki.signer("a"), now_tai_us()
    kinds = [signer_kind(signer.sign(cam_packet(signer), start + k * CAM_PERIOD_US)) for k in range(21)]
    assert [k for k, kind in enumerate(kinds) if kind == "certificate"] == [0, 10, 20]
    assert signer.full_certificate_count == 3 and signer.signed_count == 21


def test_a_denm_always_carries_the_full_certificate_and_where_it_was_generated(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    signer.sign(cam_packet(signer), now)
    envelope = parse_signed_data(signer.sign(denm_packet(signer), now + CAM_PERIOD_US)[4:])
    assert envelope.signer[0] == "certificate" and envelope.psid == PSID_DENM
    assert envelope.location is not None and envelope.location.latitude == 577_089_000


def test_each_message_is_signed_under_its_own_psid(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    psids = [parse_signed_data(signer.sign(make(signer), now)[4:]).psid
             for make in (cam_packet, denm_packet, iclcm_packet)]
    assert psids == [PSID_CAM, PSID_DENM, PSID_ICLCM]


def test_a_new_station_heard_makes_the_next_cam_carry_the_full_certificate(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    signer.sign(cam_packet(signer), now)
    assert signer_kind(signer.sign(cam_packet(signer), now + CAM_PERIOD_US)) == "digest"
    signer.request_full_certificate()
    assert signer_kind(signer.sign(cam_packet(signer), now + 2 * CAM_PERIOD_US)) == "certificate"
    assert signer_kind(signer.sign(cam_packet(signer), now + 3 * CAM_PERIOD_US)) == "digest"


def test_rotating_the_pseudonym_changes_ticket_station_id_and_mac_together_and_sends_the_new_certificate(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    signer.sign(cam_packet(signer), now)
    before = signer.identity
    after = signer.rotate_pseudonym()
    assert after.ticket.digest != before.ticket.digest
    assert after.station_id != before.station_id and after.mac != before.mac
    assert after.mac[0] & 0x03 == 0x02  # locally administered, unicast
    secured = signer.sign(cam_packet(signer), now + CAM_PERIOD_US)
    assert signer_kind(secured) == "certificate"
    assert SecurityVerifier(p256_pki.store()).verify(secured, now).signer_digest == after.ticket.digest


def test_a_packet_built_with_the_previous_station_id_or_mac_is_not_signed_after_a_rotation(p256_pki):
    signer = p256_pki.signer("a")
    stale = cam_packet(signer)
    signer.rotate_pseudonym()
    with pytest.raises(ValueError, match="MAC"):
        signer.sign(stale, now_tai_us())


def test_the_pseudonym_is_kept_while_a_manoeuvre_lock_is_held_and_changes_once_released(p256_pki):
    signer = p256_pki.signer("a")
    before = signer.identity
    with signer.manoeuvre_lock("platoon_merge"):
        with pytest.raises(PseudonymChangeRefused, match="platoon_merge"):
            signer.rotate_pseudonym()
        assert signer.identity is before and signer.locked_by == {"platoon_merge"}
    assert signer.rotate_pseudonym() is not before


def test_a_signer_with_a_single_ticket_refuses_to_rotate(p256_pki):
    signer = SecuredPacketSigner(p256_pki.tickets["a"][:1])
    with pytest.raises(PseudonymChangeRefused, match="one authorisation ticket"):
        signer.rotate_pseudonym()
