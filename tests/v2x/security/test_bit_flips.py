"""Every single-bit change of a signed packet is refused with a counted reason, and nothing crashes."""

import random

from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import US_PER_S

from .signed import cam_packet, denm_packet, now_tai_us

BITS_PER_BYTE = 8
SEED = 1609
SAMPLE_SIZE = 500
# Basic header bits outside the signature by design (EN 302 636-4-1: routers rewrite them hop by hop):
# byte 1 reserved, byte 2 lifetime, byte 3 remaining hop limit; and bit 3, the version's low bit, since
# versions 0 (GCDC 2016) and 1 are both accepted.
UNSIGNED_BASIC_HEADER_BITS = {3} | set(range(8, 32))
# rSig's choice tag (x-only 0x80) is not signed and real stations send the compressed forms, which carry the
# same r: the bit turning x-only into compressed-y-0 (0x82) leaves a valid packet (IEEE 1609.2 allows it).
# The tag is followed by r and s (32 bytes each).
RSIG_TAG_FROM_END = 65
RSIG_FORM_BIT_IN_TAG = 6
# The same holds for the r of the certificate a packet carries in full, which ends just before the packet's
# signature (its choice tag, then the 65 bytes above): a certificate is hashed with its r as x-only (IEEE 1609.2
# 6.4.3), so its digest and the packet's signer hash do not change with the form of its r.
CERTIFICATE_RSIG_TAG_FROM_END = RSIG_TAG_FROM_END + 1 + RSIG_TAG_FROM_END


def rsig_form_bit(packet: bytes, tag_from_end: int = RSIG_TAG_FROM_END) -> int:
    return (len(packet) - tag_from_end) * BITS_PER_BYTE + RSIG_FORM_BIT_IN_TAG


def flipped(packet: bytes, bit: int) -> bytes:
    changed = bytearray(packet)
    changed[bit // BITS_PER_BYTE] ^= 0x80 >> (bit % BITS_PER_BYTE)
    return bytes(changed)


def signed_pair(pki):
    """A learned verifier, a packet carrying the full certificate and one carrying the digest."""
    signer, now = pki.signer("a"), now_tai_us()
    full = signer.sign(cam_packet(signer), now)
    digest = signer.sign(cam_packet(signer), now + US_PER_S // 10)
    verifier = SecurityVerifier(pki.store())
    assert verifier.verify(full, now).ok and verifier.verify(digest, now).ok
    return verifier, now, full, digest


def outcomes(verifier, packet, now, bits):
    failures = {}
    for bit in bits:
        before = sum(verifier.rejected_by_reason.values())
        result = verifier.verify(flipped(packet, bit), now)
        if result.ok:
            failures[bit] = None
        else:
            assert isinstance(result.reason, RejectReason)
            assert sum(verifier.rejected_by_reason.values()) == before + 1
            failures[bit] = result.reason
    return failures


def secured_bits(packet: bytes) -> range:
    return range(BASIC_HEADER_SIZE * BITS_PER_BYTE, len(packet) * BITS_PER_BYTE)


def test_flipping_any_single_bit_of_the_secured_part_of_a_digest_signed_cam_makes_it_fail_with_a_counted_reason(pki):
    verifier, now, _, digest = signed_pair(pki)
    results = outcomes(verifier, digest, now, secured_bits(digest))
    assert [bit for bit, reason in results.items() if reason is None] == [rsig_form_bit(digest)]
    assert {RejectReason.INVALID_SIGNATURE, RejectReason.UNKNOWN_SIGNER_DIGEST} <= set(results.values())


def test_flipping_a_seeded_sample_of_bits_of_a_cam_with_its_certificate_never_passes_nor_spoils_the_cache(pki):
    verifier, now, full, digest = signed_pair(pki)
    bits = set(random.Random(SEED).sample(secured_bits(full), SAMPLE_SIZE)) - {
        rsig_form_bit(full), rsig_form_bit(full, CERTIFICATE_RSIG_TAG_FROM_END)}
    results = outcomes(verifier, full, now, bits)
    assert [bit for bit, reason in results.items() if reason is None] == []
    assert RejectReason.INVALID_CERTIFICATE_SIGNATURE in results.values()
    # the learned ticket is still there, untouched by the forgeries
    assert verifier.verify(digest, now).ok


def test_a_denm_is_as_tamper_proof_as_a_cam(p256_pki):
    signer, now = p256_pki.signer("a"), now_tai_us()
    packet = signer.sign(denm_packet(signer), now)
    verifier = SecurityVerifier(p256_pki.store())
    bits = set(random.Random(SEED).sample(secured_bits(packet), SAMPLE_SIZE)) - {rsig_form_bit(packet)}
    assert None not in outcomes(verifier, packet, now, bits).values()


def test_in_the_basic_header_only_the_hop_by_hop_fields_and_the_version_low_bit_are_left_unchecked(p256_pki):
    verifier, now, full, _ = signed_pair(p256_pki)
    results = outcomes(verifier, full, now, range(BASIC_HEADER_SIZE * BITS_PER_BYTE))
    assert {bit for bit, reason in results.items() if reason is None} == UNSIGNED_BASIC_HEADER_BITS


def test_every_truncation_of_a_signed_packet_is_refused_without_a_crash(p256_pki):
    verifier, now, full, _ = signed_pair(p256_pki)
    for length in range(len(full)):
        result = verifier.verify(full[:length], now)
        assert not result.ok and isinstance(result.reason, RejectReason)
