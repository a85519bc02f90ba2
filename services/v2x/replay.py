"""`coopdrive v2x replay`: a capture's GeoNetworking packets to a radio-box UDP port at their recorded pace.

    summary = replay_capture("drive.pcap", ("127.0.0.1", 4401), rate=1.0)

Each packet goes out as one datagram holding the GN packet from its basic header on, exactly what the radio
box forwards to the v2x service (services/v2x/link.py): no Ethernet or 802.11 header. Packet k leaves at
(t_k - t_0) / rate after the first, so a live service hears the capture's rhythm; secured packets go out as
recorded, signatures intact.
"""

from __future__ import annotations

import socket
import time
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import dpkt

ETHERTYPE_GEONETWORKING = 0x8947
LINKTYPE_ETHERNET = 1
# Bare GeoNetworking (what a UDP radio bridge records) on the first user link type.
LINKTYPE_BARE_GN = 147
ETHERNET_HEADER_SIZE = 14
_PCAPNG_MAGIC = b"\x0a\x0d\x0d\x0a"


class ReplayError(ValueError):
    """A capture that cannot be replayed (not pcap/pcapng); str() says why."""


@dataclass(frozen=True)
class CapturePacket:
    time_s: float
    gn_packet: bytes


@dataclass
class ReplaySummary:
    sent: int = 0
    send_errors: int = 0
    # Frames that carry no GeoNetworking packet, by why (e.g. "ethertype 0x0800", "link type 105").
    skipped: Counter = field(default_factory=Counter)
    duration_s: float = 0.0


def capture_packets(path: str | Path, skipped: Counter | None = None) -> Iterator[CapturePacket]:
    """The GN packets of an Ethernet or bare-GN pcap/pcapng, with their capture times.

    Kept small on purpose: services/v2x/capture.py (read_gn_packets) reads every link type real captures use
    and replaces this function once both are on one branch."""
    skipped = Counter() if skipped is None else skipped
    with open(path, "rb") as stream:
        head = stream.read(4)
        stream.seek(0)
        try:
            reader = dpkt.pcapng.Reader(stream) if head == _PCAPNG_MAGIC else dpkt.pcap.Reader(stream)
        except (ValueError, dpkt.Error) as error:
            raise ReplayError(f"{path}: not a pcap or pcapng file ({error})") from None
        link_type = reader.datalink()
        for time_s, data in reader:
            packet = _gn_of_frame(link_type, bytes(data))
            if isinstance(packet, str):
                skipped[packet] += 1
            else:
                yield CapturePacket(float(time_s), packet)


def _gn_of_frame(link_type: int, frame: bytes) -> bytes | str:
    """The GN packet of a frame, or why there is none."""
    if link_type == LINKTYPE_BARE_GN:
        return frame
    if link_type != LINKTYPE_ETHERNET:
        return f"link type {link_type}"
    if len(frame) < ETHERNET_HEADER_SIZE:
        return "short frame"
    ethernet = dpkt.ethernet.Ethernet(frame)
    if ethernet.type != ETHERTYPE_GEONETWORKING:
        return f"ethertype 0x{ethernet.type:04x}"
    return ethernet.data if isinstance(ethernet.data, bytes) else bytes(ethernet.data)


def replay_capture(path: str | Path, address: tuple[str, int], rate: float = 1.0,
                   sleep: Callable[[float], None] = time.sleep,
                   monotonic: Callable[[], float] = time.monotonic) -> ReplaySummary:
    """Send every GN packet of the capture to address at the recorded pace scaled by rate (2.0: twice as fast)."""
    if not rate > 0:
        raise ReplayError(f"--rate {rate}: must be above 0")
    summary = ReplaySummary()
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        first_s = start_s = None
        for packet in capture_packets(path, summary.skipped):
            if first_s is None:
                first_s, start_s = packet.time_s, monotonic()
            # Capture clocks may step back: never wait for a packet recorded before the previous one.
            wait_s = start_s + max(packet.time_s - first_s, 0.0) / rate - monotonic()
            if wait_s > 0:
                sleep(wait_s)
            try:
                sock.sendto(packet.gn_packet, address)
                summary.sent += 1
            except OSError:
                summary.send_errors += 1
        if start_s is not None:
            summary.duration_s = monotonic() - start_s
    return summary
