"""The security result (verified / fresh / trusted) and what each mode drops, on test-PKI and real packets."""

import random

import pytest

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.inspection import UNSIGNED, PacketInspector, SecurityResult, mode_drop_reason
from coopdrive.v2x.security.pki import create_untrusted_pki, tamper_packet
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.timebase import US_PER_S
from tests.shared_data import shared_file

from .signed import cam_packet, now_tai_us

SEED = 1609
MUTATIONS = 1500


def test_a_digest_signer_heard_in_full_from_an_earlier_packet_verifies_and_one_never_heard_is_unknown(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    full, digest = signer.sign(cam_packet(signer), now), signer.sign(cam_packet(signer), now + 1)
    stranger = PacketInspector(CertificateStore()).inspect(digest, now).security
    assert (stranger.verified, stranger.reason, stranger.signer) == (None, RejectReason.UNKNOWN_SIGNER_DIGEST, "digest")
    inspector = PacketInspector(CertificateStore())
    inspector.inspect(full, now)
    learned = inspector.inspect(digest, now).security
    assert (learned.verified, learned.fresh, learned.trusted, learned.reason) == (True, True, None, None)
    assert learned.signer_digest == signer.identity.ticket.digest


def test_trust_is_true_only_for_a_chain_to_a_configured_root(p256_pki, tmp_path):
    now = now_tai_us()
    ours, rogue = p256_pki.signer("a"), create_untrusted_pki(tmp_path / "rogue").signer("rogue")
    inspector = PacketInspector(p256_pki.store())
    assert inspector.inspect(ours.sign(cam_packet(ours), now), now).security.trusted is True
    refused = inspector.inspect(rogue.sign(cam_packet(rogue), now), now).security
    assert (refused.verified, refused.trusted, refused.reason) == (True, False, RejectReason.UNKNOWN_ISSUER)


def test_a_stale_packet_is_still_verified_but_not_fresh_and_without_a_clock_freshness_is_not_judged(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    old = signer.sign(cam_packet(signer), now - 5 * US_PER_S)
    judged = PacketInspector(CertificateStore()).inspect(old, now).security
    assert (judged.verified, judged.fresh, judged.reason) == (True, False, RejectReason.STALE_GENERATION_TIME)
    assert PacketInspector(CertificateStore()).inspect(old, None).security.fresh is None


def test_a_tampered_packet_is_unwrapped_with_verified_false(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    inspected = PacketInspector(CertificateStore()).inspect(tamper_packet(signer.sign(cam_packet(signer), now)), now)
    assert (inspected.security.verified, inspected.security.reason) == (False, RejectReason.INVALID_SIGNATURE)
    assert inspected.unsecured_packet is not None


GOOD = SecurityResult(True, "digest", b"\x01" * 8, verified=True, fresh=True, trusted=True)
UNTRUSTED = SecurityResult(True, "digest", b"\x01" * 8, verified=True, fresh=True, trusted=False,
                           reason=RejectReason.UNTRUSTED_ROOT)
UNKNOWN = SecurityResult(True, "digest", b"\x01" * 8, reason=RejectReason.UNKNOWN_SIGNER_DIGEST)
INVALID = SecurityResult(True, "digest", b"\x01" * 8, verified=False, reason=RejectReason.INVALID_SIGNATURE)
STALE = SecurityResult(True, "digest", b"\x01" * 8, verified=True, fresh=False,
                       reason=RejectReason.STALE_GENERATION_TIME)


@pytest.mark.parametrize(("mode", "dropped"), [
    (SecurityMode.OFF, {}),
    (SecurityMode.SIGN_ONLY, {}),
    (SecurityMode.SIGN_AND_VERIFY, {"invalid": "invalid_signature", "stale": "stale_generation_time"}),
    (SecurityMode.VERIFY_REQUIRED, {"unsigned": "unsecured_packet_refused", "untrusted": "untrusted",
                                    "unknown": "unknown_signer_digest", "invalid": "invalid_signature",
                                    "stale": "stale_generation_time"}),
])
def test_each_mode_drops_only_what_it_says(mode, dropped):
    results = {"good": GOOD, "unsigned": UNSIGNED, "untrusted": UNTRUSTED, "unknown": UNKNOWN, "invalid": INVALID,
               "stale": STALE}
    outcome = {name: mode_drop_reason(mode, result) for name, result in results.items()}
    assert {name: reason.value for name, reason in outcome.items() if reason is not None} == dropped


def test_mutated_real_signed_packets_never_raise_and_never_verify_unless_unchanged():
    packets = [frame.gn_packet for frame in read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))]
    signed = [packet for packet in packets if packet[0] & 0x0F == 2]
    rng = random.Random(SEED)
    inspector = PacketInspector(CertificateStore())
    verified_mutants = 0
    for _ in range(MUTATIONS):
        mutant = bytearray(rng.choice(signed))
        if rng.random() < 0.2:
            del mutant[rng.randrange(4, len(mutant)):]
        else:
            position = rng.randrange(4, len(mutant))
            mutant[position] ^= 1 << rng.randrange(8)
        result = inspector.inspect(bytes(mutant), None).security
        assert result.signed and isinstance(result.reason, (RejectReason, type(None)))
        verified_mutants += bool(result.verified)
    # only rewrites of rSig's form (not signed, IEEE 1609.2) may still verify: a handful at most
    assert verified_mutants <= MUTATIONS // 100
