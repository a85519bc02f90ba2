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
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from coopdrive.recording.capture import CaptureFormatError, read_capture


class ReplayError(ValueError):
    """A capture that cannot be replayed (not pcap/pcapng); str() says why."""


@dataclass
class ReplaySummary:
    sent: int = 0
    send_errors: int = 0
    # Frames that carry no GeoNetworking packet, by why (capture.UNREADABLE_REASONS, e.g. "other_ethertype").
    skipped: Counter = field(default_factory=Counter)
    duration_s: float = 0.0


def replay_capture(path: str | Path, address: tuple[str, int], rate: float = 1.0,
                   sleep: Callable[[float], None] = time.sleep,
                   monotonic: Callable[[], float] = time.monotonic) -> ReplaySummary:
    """Send every GN packet of the capture to address at the recorded pace scaled by rate (2.0: twice as fast)."""
    if not rate > 0:
        raise ReplayError(f"--rate {rate}: must be above 0")
    summary = ReplaySummary()
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        first_s = start_s = None
        for packet in _gn_frames(path, summary.skipped):
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
