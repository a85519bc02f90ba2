"""Mutated VAMs through the v2x service's whole receive path (receive_fuzz's mutations and accounting), seeded with
the 13 VAMs FlexStack sent in shared/data/v2x/flexstack_cam_vam_beacons.pcap. The CI test runs a few thousand; the
full run is

    .venv/bin/python -m tests.v2x.service.vam_fuzz --packets 100000
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from coopdrive.recording.capture import read_gn_packets
from coopdrive.v2x.btp import BtpPort, parse_btp_b
from coopdrive.v2x.geonet import parse_gn
from coopdrive.v2x.reasons import V2xDecodeError
from tests.shared_data import shared_file
from tests.v2x.service.receive_fuzz import FuzzOutcome, fuzz, print_outcome, start_service

CAPTURE = "v2x/flexstack_cam_vam_beacons.pcap"


def _is_vam(gn_packet: bytes) -> bool:
    try:
        return parse_btp_b(parse_gn(gn_packet).payload)[0].destination_port == BtpPort.VAM
    except V2xDecodeError:  # a beacon has no BTP header
        return False


def capture_vams() -> list[tuple[float, bytes]]:
    """FlexStack's VAMs as (capture time, GN packet)."""
    return [(frame.time_s, frame.gn_packet) for frame in read_gn_packets(shared_file(CAPTURE))
            if _is_vam(frame.gn_packet)]


def run(packets: int, folder: Path) -> FuzzOutcome:
    vams = capture_vams()
    # The clock just after the last VAM: it is fresh, the older ones too old (both paths are taken). Security off:
    # FlexStack's VAMs are unsigned.
    service, ctx, radio = start_service(folder / "rx.pcap", vams[-1][0])
    try:
        return fuzz(service, ctx, [[vam] for _, vam in vams], packets)
    finally:
        service.stop()
        radio.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--packets", type=int, default=100_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        outcome = run(args.packets, Path(folder))
    print_outcome(outcome, f" (vam {outcome.received.get('received_vam', 0)})")


if __name__ == "__main__":
    main()
