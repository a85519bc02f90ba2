"""UDP link to the radio box, and the pcap log of every packet that crosses it.

The radio box forwards each received GeoNetworking packet as one UDP datagram (no Ethernet header) and
transmits each datagram we send it. A reader thread hands datagrams to a callback; the service passes
that callback through ctx.call_soon so its own code stays on its worker thread.
"""

from __future__ import annotations

import socket
import struct
import threading
import time
from typing import BinaryIO, Callable

from coopdrive.recording.link_types import ETHERTYPE_GEONETWORKING
from coopdrive.services.v2x.link_reader import RECEIVE_POLL_S, LinkReader
from coopdrive.v2x.pcap import BROADCAST_MAC, PcapWriter
from coopdrive.v2x.timebase import US_PER_S



class CaptureLog(PcapWriter):
    """A pcap file whose frames carry each packet's own source MAC (ours when sent, the sender's when received)."""

    def __init__(self, stream: BinaryIO, own_mac: bytes):
        super().__init__(stream, own_mac)
        self._own_mac = own_mac
        self._lock = threading.Lock()

    def write_packet(self, gn_packet: bytes, time_s: float, source_mac: bytes | None = None) -> None:
        mac = source_mac if source_mac is not None and len(source_mac) == len(self._own_mac) else self._own_mac
        frame = BROADCAST_MAC + mac + struct.pack(">H", ETHERTYPE_GEONETWORKING) + gn_packet
        whole_s, fraction_us = divmod(round(time_s * US_PER_S), US_PER_S)
        with self._lock:
            self._stream.write(struct.pack("<IIII", whole_s, fraction_us, len(frame), len(frame)) + frame)
            self._stream.flush()


class UdpLink(LinkReader):
    """Sends datagrams to the radio box and reads the ones it sends us on a daemon thread."""

    def __init__(self, listen: tuple[str, int], radio: tuple[str, int], on_datagram: Callable[[bytes], None],
                 max_packet_bytes: int = 2048):
        self.radio = radio
        self._on_datagram = on_datagram
        self._max_packet_bytes = max_packet_bytes
        udp_socket = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        udp_socket.bind(listen)
        super().__init__(udp_socket, "v2x-udp")
        self.send_errors = 0
        # Lockstep reading (receive_until): datagrams read so far, and those the radio box sent that never came.
        self.received_count = 0
        self.missing_datagrams = 0

    @property
    def local_address(self) -> tuple[str, int]:
        return self._socket.getsockname()

    def send(self, datagram: bytes) -> bool:
        """False (and counted) when the OS refused the datagram, e.g. the radio box is unreachable."""
        try:
            self._socket.sendto(datagram, self.radio)
            return True
        except OSError:
            self.send_errors += 1
            return False

    def receive_until(self, total_datagrams: int, timeout_s: float) -> list[bytes]:
        """Lockstep: reads until `total_datagrams` have arrived since the link opened (the radio box's count).

        Returns the datagrams read now; fewer when the timeout passes first (counted in missing_datagrams).
        """
        datagrams: list[bytes] = []
        deadline = time.monotonic() + timeout_s
        while self.received_count < total_datagrams:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                self.missing_datagrams += total_datagrams - self.received_count
                self.received_count = total_datagrams
                break
            self._socket.settimeout(min(remaining, RECEIVE_POLL_S))
            try:
                datagrams.append(self._socket.recv(self._max_packet_bytes))
                self.received_count += 1
            except (socket.timeout, OSError):
                continue
        return datagrams

    def _receive_one(self) -> None:
        self._on_datagram(self._socket.recv(self._max_packet_bytes))


class RecordedLink:
    """The radio box under replay, where no hardware is opened: what was received arrives as the recording's
    v2x/rx packets, and what the service sends goes nowhere (counted as sent, as the live box took it)."""

    send_errors = 0
    missing_datagrams = 0

    def start(self) -> None:
        """Nothing to listen to."""

    def send(self, datagram: bytes) -> bool:
        return True

    def close(self) -> None:
        """Nothing to close."""
