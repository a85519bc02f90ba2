"""A raw link: GeoNetworking frames straight on a network interface (an 802.11p OCB interface, a Cohda-style
box's Linux interface, a veth in tests), as ETSI stacks on Linux send them: an AF_PACKET socket bound to
ethertype 0x8947, our GN MAC as the frame's source and the broadcast address as its destination.

Like UdpLink, a reader thread hands each received GN packet (the frame without its Ethernet header) to a callback.
"""

from __future__ import annotations

import errno
import socket
import struct
from typing import Callable

from coopdrive.recording.link_types import ETHERTYPE_GEONETWORKING
from coopdrive.runtime.service import HardwareUnavailable
from coopdrive.services.v2x.link_reader import LinkReader
from coopdrive.v2x.pcap import BROADCAST_MAC

ETHERNET_HEADER_BYTES = 14
MAC_BYTES = 6
# The largest frame an 802.11 OCB or Ethernet interface carries without fragmentation: header and a 1500-byte MTU.
MAX_FRAME_BYTES = ETHERNET_HEADER_BYTES + 1500
# sll_pkttype of a frame this host sent itself (linux/if_packet.h): a packet socket sees its own frames too.
PACKET_OUTGOING = 4


class RawLinkError(HardwareUnavailable):
    """The interface cannot be opened: one line naming it and why."""


def open_packet_socket(interface: str) -> socket.socket:
    """An AF_PACKET socket on `interface` for GeoNetworking frames; RawLinkError names what is wrong."""
    if not hasattr(socket, "AF_PACKET"):
        raise RawLinkError(f"v2x raw link on {interface}: raw packet sockets exist only on Linux")
    try:
        packet_socket = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETHERTYPE_GEONETWORKING))
    except PermissionError:
        raise RawLinkError(f"v2x raw link on {interface}: a raw socket needs CAP_NET_RAW (run as root, or "
                           "`setcap cap_net_raw+ep` on the interpreter, or give the container NET_RAW)") from None
    try:
        packet_socket.bind((interface, ETHERTYPE_GEONETWORKING))
    except OSError as error:
        packet_socket.close()
        if error.errno == errno.ENODEV:
            raise RawLinkError(f"v2x raw link: no network interface {interface!r} (see `ip link`)") from None
        raise RawLinkError(f"v2x raw link on {interface}: {error.strerror or error}") from None
    return packet_socket


def frame_header(source_mac: bytes) -> bytes:
    """The Ethernet header of a GN frame from source_mac: broadcast destination, ethertype 0x8947."""
    return BROADCAST_MAC + source_mac + struct.pack(">H", ETHERTYPE_GEONETWORKING)


class RawLink(LinkReader):
    """Sends GN packets as broadcast frames from our MAC and reads the others' frames on a daemon thread."""

    def __init__(self, interface: str, source_mac: bytes, on_packet: Callable[[bytes], None]):
        if len(source_mac) != MAC_BYTES:
            raise RawLinkError(f"v2x raw link on {interface}: a MAC address has {MAC_BYTES} bytes, not "
                               f"{len(source_mac)}")
        self.interface = interface
        self._header = frame_header(source_mac)
        self._source_mac = source_mac
        self._on_packet = on_packet
        super().__init__(open_packet_socket(interface), f"v2x-raw-{interface}")
        self.send_errors = 0
        # Frames refused before GeoNetworking: too short for an Ethernet header.
        self.runt_frames = 0
        # Never waited for: a raw link has no radio box to say how much it sent.
        self.missing_datagrams = 0

    def send(self, gn_packet: bytes) -> bool:
        """False (and counted) when the interface refused the frame (down, or the packet too long)."""
        try:
            self._socket.send(self._header + gn_packet)
            return True
        except OSError:
            self.send_errors += 1
            return False

    def _receive_one(self) -> None:
        frame, address = self._socket.recvfrom(MAX_FRAME_BYTES)
        self.on_frame(frame, address[2] if len(address) > 2 else 0)

    def on_frame(self, frame: bytes, packet_type: int) -> None:
        """One frame off the interface: our own (looped back to a packet socket) are dropped, the rest handed on
        without their Ethernet header."""
        if packet_type == PACKET_OUTGOING or frame[MAC_BYTES:2 * MAC_BYTES] == self._source_mac:
            return
        if len(frame) <= ETHERNET_HEADER_BYTES:
            self.runt_frames += 1
            return
        self._on_packet(frame[ETHERNET_HEADER_BYTES:])
