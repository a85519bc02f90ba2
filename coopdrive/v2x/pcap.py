"""pcap writer: Ethernet frames carrying GeoNetworking (what our v2x service logs).

Wireshark dissects GeoNetworking on ethertype 0x8947, so packets are written as Ethernet II frames.
Captures are read with coopdrive/recording/capture.py (dpkt, every link type real captures use).
"""

from __future__ import annotations

import struct
from typing import BinaryIO

from coopdrive.recording.link_types import ETHERTYPE_GEONETWORKING, LINKTYPE_ETHERNET
from coopdrive.v2x.timebase import US_PER_S

BROADCAST_MAC = b"\xff" * 6
ETHERNET_HEADER_SIZE = 14
SNAPLEN_BYTES = 65_535

_PCAP_MAGIC_US = 0xA1B2C3D4


class PcapWriter:
    """Writes GeoNetworking packets as Ethernet frames (ethertype 0x8947) into a classic pcap file."""

    def __init__(self, stream: BinaryIO, source_mac: bytes, destination_mac: bytes = BROADCAST_MAC):
        if len(source_mac) != 6 or len(destination_mac) != 6:
            raise ValueError("MAC addresses are 6 bytes")
        self._stream = stream
        self._ethernet = destination_mac + source_mac + struct.pack(">H", ETHERTYPE_GEONETWORKING)
        stream.write(struct.pack("<IHHiIII", _PCAP_MAGIC_US, 2, 4, 0, 0, SNAPLEN_BYTES, LINKTYPE_ETHERNET))

    def write(self, gn_packet: bytes, time_s: float) -> None:
        frame = self._ethernet + gn_packet
        whole_s, fraction_us = divmod(round(time_s * US_PER_S), US_PER_S)
        self._stream.write(struct.pack("<IIII", whole_s, fraction_us, len(frame), len(frame)) + frame)
