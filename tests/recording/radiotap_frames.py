"""Monitor-interface frames made from real Ethernet-framed GeoNetworking packets, as an 802.11p radio in monitor
mode records them: a radiotap header, an 802.11 QoS data frame to the broadcast address with the wildcard BSSID
(OCB), LLC/SNAP with ethertype 0x8947, and, where the radio keeps it, the frame's FCS (CRC-32)."""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import dpkt

from coopdrive.recording.link_types import LINKTYPE_RADIOTAP
from coopdrive.recording.radiotap import FLAG_BAD_FCS, FLAG_DATA_PADDED, FLAG_FCS_AT_END

BROADCAST = b"\xff" * 6
QOS_DATA_FRAME_CONTROL = bytes([0x88, 0x00])  # type data, subtype QoS data; no DS bits (OCB)
LLC_SNAP_GEONETWORKING = bytes.fromhex("aaaa03000000") + struct.pack(">H", 0x8947)
PRESENT_TSFT_FLAGS_RATE_CHANNEL_EXTENDED = (1 << 0) | (1 << 1) | (1 << 2) | (1 << 3) | (1 << 31)
RATE_6_MBPS = 12  # in 500 kb/s
CHANNEL_180_MHZ, CHANNEL_FLAGS_OFDM_5GHZ = 5900, 0x0140


def qos_data_frame(source_mac: bytes, gn_packet: bytes, sequence: int, padded: bool = False) -> bytes:
    header = (QOS_DATA_FRAME_CONTROL + b"\x00\x00" + BROADCAST + source_mac + BROADCAST
              + struct.pack("<H", sequence << 4) + b"\x00\x00")
    return header + (b"\x00\x00" if padded else b"") + LLC_SNAP_GEONETWORKING + gn_packet


def radiotap_header(flags: int | None, tsft_us: int = 0) -> bytes:
    """Without flags: the shortest header (no field). With them: TSFT, Flags, Rate and Channel behind two present
    words (the second an empty extension), aligned as radiotap.org says."""
    if flags is None:
        return struct.pack("<BBHI", 0, 0, 8, 0)
    fields = struct.pack("<4xQBBHH", tsft_us, flags, RATE_6_MBPS, CHANNEL_180_MHZ, CHANNEL_FLAGS_OFDM_5GHZ)
    length = 12 + len(fields)
    return struct.pack("<BBHII", 0, 0, length, PRESENT_TSFT_FLAGS_RATE_CHANNEL_EXTENDED, 0) + fields


def monitor_frame(ethernet_frame: bytes, sequence: int, flags: int | None) -> bytes:
    source_mac, gn_packet = ethernet_frame[6:12], ethernet_frame[14:]
    padded = flags is not None and bool(flags & FLAG_DATA_PADDED)
    frame = qos_data_frame(source_mac, gn_packet, sequence, padded)
    if flags is not None and flags & FLAG_FCS_AT_END:
        # The FCS covers the frame as sent, without the driver's padding.
        unpadded = qos_data_frame(source_mac, gn_packet, sequence)
        fcs = zlib.crc32(unpadded) ^ (0xFFFFFFFF if flags & FLAG_BAD_FCS else 0)
        frame += struct.pack("<I", fcs)
    return radiotap_header(flags, sequence) + frame


def write_monitor_capture(ethernet_capture: Path, out: Path, flags: int | None) -> None:
    with open(ethernet_capture, "rb") as source, open(out, "wb") as target:
        writer = dpkt.pcap.Writer(target, linktype=LINKTYPE_RADIOTAP)
        for sequence, (time_s, frame) in enumerate(dpkt.pcap.Reader(source)):
            writer.writepkt(monitor_frame(bytes(frame), sequence, flags), ts=time_s)


FCS_KEPT = FLAG_FCS_AT_END
FCS_KEPT_AND_PADDED = FLAG_FCS_AT_END | FLAG_DATA_PADDED
FCS_BAD = FLAG_FCS_AT_END | FLAG_BAD_FCS
