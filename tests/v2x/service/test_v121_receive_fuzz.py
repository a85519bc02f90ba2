"""Mutated TS 103 097 v1.2.1 packets reach the v2x service's receive path (the full run,
`python -m tests.v2x.service.v121_receive_fuzz`, takes 100 000): nothing raises, and every packet is accepted, taken
as a beacon or rejected under a reason."""

from .receive_fuzz import assert_every_packet_counted
from .v121_receive_fuzz import run

PACKETS = 3000


def test_3000_mutated_v121_packets_pass_the_receive_path_each_accepted_or_counted_under_a_reason(tmp_path):
    outcome = run(PACKETS, tmp_path)
    assert_every_packet_counted(outcome, PACKETS)
    assert outcome.rejected["malformed_security_envelope"] > 0
    # forgeries reach the signature check, and digest signers resolve from the certificates heard before them
    assert outcome.security["security_invalid_signature"] > 0 and outcome.security["security_verified"] > 0
    assert outcome.accepted > 0 and outcome.beacons > 0
