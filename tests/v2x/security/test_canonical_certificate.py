"""A certificate is named and hashed in its canonical form (IEEE 1609.2 6.4.3): a ticket sent with an uncompressed
key, as another open stack sends its tickets, has the digest of its compressed form, and its CAMs verify whether
they carry it in full or by that digest."""

from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.security import asn
from coopdrive.v2x.security.canonical import canonical_certificate
from coopdrive.v2x.security.certificate import Certificate
from coopdrive.v2x.security.crypto import hashed_id8
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.verifier import SecurityVerifier

from .signed import cam_packet, now_tai_us

US_PER_100_MS = 100_000


def test_a_ticket_with_an_uncompressed_key_is_named_by_the_digest_of_its_compressed_form(p256_pki):
    ticket, _ = p256_pki.issue_ticket("uncompressed", uncompressed_key=True)
    assert ticket.value["toBeSigned"]["verifyKeyIndicator"][1][1][0] == "uncompressedP256"
    compressed = asn.encode(asn.CERTIFICATE_TYPE, canonical_certificate(ticket.value))
    assert ticket.digest == hashed_id8(compressed) != hashed_id8(ticket.encoded)
    assert ticket.canonical == compressed
    assert Certificate.from_bytes(ticket.encoded).digest == ticket.digest


def test_a_signature_s_r_in_any_form_hashes_as_x_only(p256_pki):
    ticket, _ = p256_pki.issue_ticket("compressed r")
    choice, signature = ticket.value["signature"]
    assert signature["rSig"][0] == "x-only"
    with_compressed_r = {**ticket.value, "signature": (choice, {**signature, "rSig": ("compressed-y-1",
                                                                                      signature["rSig"][1])})}
    assert Certificate.from_value(with_compressed_r).digest == ticket.digest


def test_cams_signed_with_an_uncompressed_key_ticket_verify_in_full_and_by_digest(p256_pki):
    signer = SecuredPacketSigner([p256_pki.issue_ticket("uncompressed", uncompressed_key=True)])
    verifier, now = SecurityVerifier(p256_pki.store()), now_tai_us()
    in_full = signer.sign(cam_packet(signer), now)
    by_digest = signer.sign(cam_packet(signer), now + US_PER_100_MS)
    assert verifier.verify(in_full, now) == (True, None, signer.identity.ticket.digest)
    assert verifier.verify(by_digest, now + US_PER_100_MS).ok
    decoded = V2xPacketCodec().decode_packet(in_full)
    assert decoded.security.verified and decoded.security.signer_digest == signer.identity.ticket.digest
