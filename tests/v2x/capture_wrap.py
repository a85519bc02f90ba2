"""Rewrite a capture's GeoNetworking packets in the other link types real captures use (built with dpkt).

    wrap_capture(source, target, "radiotap")    # radiotap + 802.11 QoS data + LLC/SNAP, as a monitor interface
"""

from __future__ import annotations

import struct
from pathlib import Path

import dpkt

from coopdrive.recording.capture import read_capture
from coopdrive.recording.link_types import ETHERTYPE_GEONETWORKING, LINK_TYPE_OF_NAME

BROADCAST = b"\xff" * 6
UNKNOWN_MAC = b"\x02\x00\x00\x00\x00\x00"
# Radiotap v0 with no fields; 802.11 QoS data (type 2, subtype 8), neither to nor from DS, as OCB sends.
RADIOTAP_EMPTY = struct.pack("<BBHI", 0, 0, 8, 0)
QOS_DATA_FRAME_CONTROL = b"\x88\x00"
LLC_SNAP_GN = b"\xaa\xaa\x03\x00\x00\x00" + struct.pack(">H", ETHERTYPE_GEONETWORKING)
SLL_BROADCAST = 1
ARPHRD_IEEE80211 = 801


def ieee80211(source_mac: bytes, gn_packet: bytes) -> bytes:
    header = QOS_DATA_FRAME_CONTROL + bytes(2) + BROADCAST + source_mac + BROADCAST + bytes(2) + bytes(2)
    return header + LLC_SNAP_GN + gn_packet


def wrapped(link_type: str, source_mac: bytes, gn_packet: bytes) -> bytes:
    if link_type == "ethernet":
        return BROADCAST + source_mac + struct.pack(">H", ETHERTYPE_GEONETWORKING) + gn_packet
    if link_type == "ieee802_11":
        return ieee80211(source_mac, gn_packet)
    if link_type == "radiotap":
        return RADIOTAP_EMPTY + ieee80211(source_mac, gn_packet)
    if link_type == "linux_sll":
        return struct.pack(">HHH8sH", SLL_BROADCAST, ARPHRD_IEEE80211, 6, source_mac, ETHERTYPE_GEONETWORKING) \
            + gn_packet
    if link_type == "linux_sll2":
        return struct.pack(">HHiHBB8s", ETHERTYPE_GEONETWORKING, 0, 1, ARPHRD_IEEE80211, SLL_BROADCAST, 6,
                           source_mac) + gn_packet
    raise ValueError(link_type)


def wrap_capture(source: Path, target: Path, link_type: str, extra_frames: tuple[bytes, ...] = ()) -> Path:
    """target: source's GN packets in link_type (same times, same source MACs), then extra_frames as they are."""
    with open(target, "wb") as stream:
        writer = dpkt.pcap.Writer(stream, snaplen=65535, linktype=LINK_TYPE_OF_NAME[link_type],
                                  nano=True)
        last_s = 0.0
        for frame in read_capture(source):
            if frame.gn_packet is not None:
                writer.writepkt(wrapped(link_type, frame.source_mac or UNKNOWN_MAC, frame.gn_packet), frame.time_s)
                last_s = frame.time_s
        for extra in extra_frames:
            writer.writepkt(extra, last_s)
    return target
