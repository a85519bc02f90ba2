"""Fuzzing reaches the v2x service's receive path: 5000 mutated real and own packets (the full run,
`python -m tests.v2x.service.receive_fuzz`, takes 100 000) through V2xService.on_datagram, the station table and
the status; nothing raises, no packet stalls, and every packet is accepted, ignored as ours, taken as a beacon or
rejected under a reason."""

from coopdrive.services.v2x.plausibility import PlausibilityReason

from .receive_fuzz import assert_every_packet_counted, run

PACKETS = 5000


def test_5000_mutated_packets_pass_the_receive_path_each_accepted_or_counted_under_a_reason(tmp_path):
    outcome = run(PACKETS, tmp_path)
    assert_every_packet_counted(outcome, PACKETS)
    # every stage refused something: the security envelope, the decoder, plausibility; and something got through
    assert outcome.rejected["malformed_security_envelope"] > 0
    # forged packets reach the signature check (sign_and_verify counts them, then delivers them marked)
    assert outcome.security["security_invalid_signature"] > 0 and outcome.security["security_verified"] > 0
    assert outcome.rejected["unknown_btp_port"] > 0 and outcome.rejected["malformed_asn1"] > 0
    assert sum(outcome.rejected[reason.value] for reason in PlausibilityReason) > 0
    assert outcome.accepted > 0 and outcome.stations_listed_max > 0
