"""Mutated VAMs through the v2x service's whole receive path (receive_fuzz's mutations and accounting), seeded with
the 13 VAMs FlexStack sent in shared/data/v2x/flexstack_cam_vam_beacons.pcap. The CI test runs a few thousand; the
full run is

    .venv/bin/python -m tests.v2x.service.vam_fuzz --packets 100000
"""

from __future__ import annotations

import argparse
import socket
import tempfile
from pathlib import Path

from coopdrive.recording.capture import read_gn_packets
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.v2x.service import V2xService
from coopdrive.v2x.btp import BtpPort, parse_btp_b
from coopdrive.v2x.geonet import parse_gn
from coopdrive.v2x.reasons import V2xDecodeError
from coopdrive.v2x.release2 import release2_spec
from tests.shared_data import shared_file
from tests.v2x.service.receive_fuzz import FuzzOutcome, fuzz, print_outcome
from tests.v2x.udp_socket import loopback_udp_socket

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


def started_service(folder: Path, now_s: float) -> tuple[V2xService, MemoryContext, socket.socket]:
    """A v2x service with security off (FlexStack's VAMs are unsigned), its clock at now_s."""
    release2_spec()  # compiled before the clock runs: a packet's time is its own work
    radio = loopback_udp_socket()
    ctx = MemoryContext(queue_calls=True, opens_hardware=True)
    ctx.clock.set(now_s)
    config = V2xService.Config.model_validate({
        "link": {"radio_port": radio.getsockname()[1], "listen_port": 0}, "station_id": 1001,
        "vehicle_mac": "02:00:00:00:10:01", "pcap_path": str(folder / "rx.pcap"), "send_iclcm": False})
    service = V2xService(config, ctx)
    service.start()
    return service, ctx, radio


def run(packets: int, folder: Path) -> FuzzOutcome:
    vams = capture_vams()
    # The clock just after the last VAM: it is fresh, the older ones too old (both paths are taken).
    service, ctx, radio = started_service(folder, vams[-1][0])
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
