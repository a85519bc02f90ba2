"""`coopdrive v2x replay`: a capture's GeoNetworking packets at their recorded pace, to a radio-box UDP port or
onto a network interface.

    summary = replay_capture("drive.pcap", UdpSink(("127.0.0.1", 4401)), rate=1.0)
    summary = replay_capture("drive.pcap", RawSink("wlan1"), rate=1.0)

To a UDP port each packet goes out as one datagram holding the GN packet from its basic header on, exactly what
the radio box forwards to the v2x service (services/v2x/link.py): no Ethernet or 802.11 header. Onto an interface
(an 802.11p OCB interface, a veth) each goes out as a broadcast Ethernet frame of ethertype 0x8947 from the MAC
address the capture shows for its sender, as the station sent it (raw_link.py). Packet k leaves at
(t_k - t_0) / rate after the first, so a live receiver hears the capture's rhythm; secured packets go out as
recorded, signatures intact.
"""

from __future__ import annotations

import socket
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Protocol

from coopdrive.recording.capture import CaptureFormatError, CapturedFrame, read_capture
from coopdrive.services.v2x.raw_link import frame_header, open_packet_socket

# The sender's MAC where the capture shows none (a capture of GN packets without a link header): locally
# administered, unicast.
UNKNOWN_SENDER_MAC = bytes.fromhex("020000000001")


class ReplayError(ValueError):
    """A capture that cannot be replayed (not pcap/pcapng); str() says why."""


@dataclass
class ReplaySummary:
    sent: int = 0
    send_errors: int = 0
    # Frames that carry no GeoNetworking packet, by why (capture.UNREADABLE_REASONS, e.g. "other_ethertype").
    skipped: Counter = field(default_factory=Counter)
    duration_s: float = 0.0


class PacketSink(Protocol):
    """Where a replayed frame goes; send raises OSError when it could not go."""

    def send(self, frame: CapturedFrame) -> None: ...

    def close(self) -> None: ...


class UdpSink:
    """To a radio-box UDP port: the GN packet alone."""

    def __init__(self, address: tuple[str, int]):
        self.address = address
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)

    def send(self, frame: CapturedFrame) -> None:
        self._socket.sendto(frame.gn_packet, self.address)

    def close(self) -> None:
        self._socket.close()


class RawSink:
    """Onto a network interface: the GN packet in a broadcast Ethernet frame from its sender's MAC. RawLinkError
    (one line) when the interface is missing or the process may not open a raw socket."""

    def __init__(self, interface: str):
        self.interface = interface
        self._socket = open_packet_socket(interface)

    def send(self, frame: CapturedFrame) -> None:
        self._socket.send(frame_header(frame.source_mac or UNKNOWN_SENDER_MAC) + frame.gn_packet)

    def close(self) -> None:
        self._socket.close()


def replay_capture(path: str | Path, sink: PacketSink, rate: float = 1.0,
                   sleep: Callable[[float], None] = time.sleep,
                   monotonic: Callable[[], float] = time.monotonic) -> ReplaySummary:
    """Send every GN packet of the capture to the sink at the recorded pace scaled by rate (2.0: twice as fast);
    the sink is closed at the end."""
    if not rate > 0:
        sink.close()
        raise ReplayError(f"--rate {rate}: must be above 0")
    summary = ReplaySummary()
    try:
        first_s = start_s = None
        for packet in _gn_frames(path, summary.skipped):
            if first_s is None:
                first_s, start_s = packet.time_s, monotonic()
            # Capture clocks may step back: never wait for a packet recorded before the previous one.
            wait_s = start_s + max(packet.time_s - first_s, 0.0) / rate - monotonic()
            if wait_s > 0:
                sleep(wait_s)
            try:
                sink.send(packet)
                summary.sent += 1
            except OSError:
                summary.send_errors += 1
        if start_s is not None:
            summary.duration_s = monotonic() - start_s
    finally:
        sink.close()
    return summary


def _gn_frames(path: str | Path, skipped: Counter):
    """The capture's frames that carry GeoNetworking; the others counted in skipped by why."""
    try:
        for frame in read_capture(path):
            if frame.gn_packet is None:
                skipped[frame.unreadable] += 1
            else:
                yield frame
    except CaptureFormatError as error:
        raise ReplayError(f"{path}: not a pcap or pcapng file ({error})") from None
