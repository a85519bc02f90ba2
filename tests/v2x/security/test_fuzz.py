"""Random bytes and random multi-byte damage never crash the verifier: a counted reason comes back."""

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from coopdrive.v2x.geonet import BASIC_HEADER_SIZE
from coopdrive.v2x.reasons import RejectReason
from coopdrive.v2x.security.verifier import SecurityVerifier

from .signed import cam_packet, now_tai_us

SECURED_GN_V1 = b"\x12\x00\x05\x01"
EXAMPLES = 150
_signed: dict[int, tuple[bytes, int]] = {}


def check(verifier: SecurityVerifier, packet: bytes, now: int) -> None:
    before = sum(verifier.rejected_by_reason.values())
    result = verifier.verify(packet, now)
    if not result.ok:
        assert isinstance(result.reason, RejectReason)
        assert sum(verifier.rejected_by_reason.values()) == before + 1


@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(body=st.binary(max_size=400))
def test_random_bytes_after_a_secured_basic_header_are_refused_with_a_reason(p256_pki, body):
    check(SecurityVerifier(p256_pki.store()), SECURED_GN_V1 + body, now_tai_us())


@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(damage=st.lists(st.tuples(st.integers(min_value=0), st.integers(min_value=1, max_value=255)),
                       min_size=1, max_size=6))
def test_several_damaged_bytes_in_a_signed_cam_never_crash_and_never_pass(p256_pki, damage):
    if id(p256_pki) not in _signed:
        signer, now = p256_pki.signer("a"), now_tai_us()
        _signed[id(p256_pki)] = signer.sign(cam_packet(signer), now), now
    original, now = _signed[id(p256_pki)]
    packet = bytearray(original)
    for position, mask in damage:
        # the basic header is outside the signature (see test_bit_flips): damage the secured part only
        packet[BASIC_HEADER_SIZE + position % (len(packet) - BASIC_HEADER_SIZE)] ^= mask
    assume(bytes(packet) != original)
    verifier = SecurityVerifier(p256_pki.store())
    check(verifier, bytes(packet), now)
    assert not verifier.verify(bytes(packet), now).ok
