"""Mutated SPATEM, MAPEM, SREM and SSEM through the v2x service's whole receive path (receive_fuzz's service,
mutations and accounting). Seeds: the real signed SPATEM of shared/data/v2x and the hand-written messages of
tests/v2x/infrastructure_messages.py in both protocol versions. The CI test runs a few thousand; the full run is

    .venv/bin/python -m tests.v2x.service.infrastructure_fuzz --packets 100000
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v2x.btp import BtpPort
from coopdrive.v2x.infrastructure import InfrastructureCodec
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.timebase import unix_s_from_tai_ms
from tests.shared_data import shared_file
from tests.v2x import infrastructure_messages as messages
from tests.v2x.service.receive_fuzz import FuzzOutcome, print_outcome, run_in_service, signing_with, start_service

REAL_SPATEM_INDEX = 3
# Its generation time (TAI ms since 2004, in its signed header); the service's clock starts just after, so that
# the signature check (sign_and_verify) finds it fresh.
REAL_SPATEM_GENERATION_TAI_MS = 627_816_430_060
AFTER_GENERATION_S = 0.1
BUILDERS = {"SPATEM": messages.spatem, "MAPEM": messages.mapem, "SREM": messages.srem, "SSEM": messages.ssem}


def seeds() -> list[bytes]:
    packets = read_gn_packets(shared_file("v2x/considerit_signed_testvectors.pcap"))
    real = [packet.gn_packet for packet in packets][REAL_SPATEM_INDEX]
    own = [messages.gn_packet(BtpPort[kind], messages.encoded(kind, build(version)))
           for kind, build in BUILDERS.items() for version in (1, 2)]
    return [real, *own]


def prepared_clock_s(folder: Path) -> float:
    """A test PKI of its own in folder (receive_fuzz's service signs and verifies with it) and the roadside modules
    compiled before the clock runs (a packet's time is its own work); returns the service's clock: just after the
    real SPATEM was sent."""
    create_test_pki(folder / "pki", ["ego"])
    InfrastructureCodec.spec()
    return unix_s_from_tai_ms(REAL_SPATEM_GENERATION_TAI_MS) + AFTER_GENERATION_S


def started_service(folder: Path):
    """receive_fuzz's service on folder's PKI, its clock just after the real SPATEM was sent."""
    return start_service(folder / "rx.pcap", prepared_clock_s(folder), signing_with(folder / "pki"))


def run(packets: int, folder: Path) -> tuple[FuzzOutcome, dict[str, int]]:
    """The outcome and what was delivered by kind (received_spatem, ...). One group per seed: each message kind is
    drawn as often as the others."""
    now_s = prepared_clock_s(folder)
    outcome = run_in_service(folder, now_s, [[seed] for seed in seeds()], packets)
    return outcome, outcome.received


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--packets", type=int, default=100_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        outcome, counters = run(args.packets, Path(folder))
    received = ", ".join(f"{name.removeprefix('received_')} {count}" for name, count in sorted(counters.items())
                         if name.startswith("received_"))
    print_outcome(outcome, f" ({received})")

if __name__ == "__main__":
    main()
