"""pcap writer (Ethernet frames carrying GeoNetworking) and a reader for pcap and pcapng files.

Wireshark dissects GeoNetworking on ethertype 0x8947, so packets are written as Ethernet II frames.
"""

from __future__ import annotations

import struct
from collections.abc import Iterator
from dataclasses import dataclass
from typing import BinaryIO

ETHERTYPE_GEONETWORKING = 0x8947
LINKTYPE_ETHERNET = 1
# Captures of GeoNetworking carried bare (e.g. from a UDP radio bridge) use the first user link type.
LINKTYPE_USER0_BARE_GN = 147
BROADCAST_MAC = b"\xff" * 6
ETHERNET_HEADER_SIZE = 14
SNAPLEN_BYTES = 65_535
US_PER_S = 1_000_000

_PCAP_MAGIC_US = 0xA1B2C3D4
_PCAP_MAGIC_NS = 0xA1B23C4D
_PCAPNG_SECTION_HEADER = 0x0A0D0D0A
_PCAPNG_BYTE_ORDER_MAGIC = 0x1A2B3C4D
_PCAPNG_INTERFACE_DESCRIPTION = 0x00000001
_PCAPNG_SIMPLE_PACKET = 0x00000003
_PCAPNG_ENHANCED_PACKET = 0x00000006
_PCAPNG_IF_TSRESOL = 9
_DEFAULT_TSRESOL = 6


class PcapFormatError(ValueError):
    """A file that is neither pcap nor pcapng, or is cut in the middle of a header."""


@dataclass(frozen=True)
class CapturedFrame:
    time_s: float
    link_type: int
    data: bytes


@dataclass(frozen=True)
class EthernetFrame:
    destination_mac: bytes
    source_mac: bytes
    ethertype: int
    payload: bytes


def parse_ethernet(frame: bytes) -> EthernetFrame:
    if len(frame) < ETHERNET_HEADER_SIZE:
        raise ValueError(f"Ethernet frame of {len(frame)} bytes")
    (ethertype,) = struct.unpack_from(">H", frame, 12)
    return EthernetFrame(frame[0:6], frame[6:12], ethertype, frame[ETHERNET_HEADER_SIZE:])


@dataclass(frozen=True)
class CapturedGnPacket:
    time_s: float
    source_mac: bytes | None
    gn_packet: bytes


def read_gn_packets(stream: BinaryIO) -> Iterator[CapturedGnPacket]:
    """The GeoNetworking packets of a capture: Ethernet frames with ethertype 0x8947, or bare GN (USER0).

    Frames of other ethertypes or link types, and Ethernet frames too short to hold a header, are skipped.
    """
    for frame in read_frames(stream):
        if frame.link_type == LINKTYPE_USER0_BARE_GN:
            yield CapturedGnPacket(frame.time_s, None, frame.data)
        elif frame.link_type == LINKTYPE_ETHERNET and len(frame.data) >= ETHERNET_HEADER_SIZE:
            ethernet = parse_ethernet(frame.data)
            if ethernet.ethertype == ETHERTYPE_GEONETWORKING:
                yield CapturedGnPacket(frame.time_s, ethernet.source_mac, ethernet.payload)


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


def read_frames(stream: BinaryIO) -> Iterator[CapturedFrame]:
    """Frames of a pcap or pcapng stream, in file order."""
    head = stream.read(4)
    if len(head) < 4:
        raise PcapFormatError("file shorter than a magic number")
    if struct.unpack("<I", head)[0] == _PCAPNG_SECTION_HEADER:
        yield from _read_pcapng(stream, head)
    else:
        yield from _read_pcap(stream, head)


def _read_exact(stream: BinaryIO, size: int, what: str) -> bytes:
    data = stream.read(size)
    if len(data) != size:
        raise PcapFormatError(f"truncated {what}")
    return data


def _read_pcap(stream: BinaryIO, magic_bytes: bytes) -> Iterator[CapturedFrame]:
    for order in "<>":
        (magic,) = struct.unpack(order + "I", magic_bytes)
        if magic in (_PCAP_MAGIC_US, _PCAP_MAGIC_NS):
            break
    else:
        raise PcapFormatError(f"unknown magic {magic_bytes.hex()}")
    fraction_per_s = US_PER_S if magic == _PCAP_MAGIC_US else 1_000_000_000
    _, _, _, _, _, link_type = struct.unpack(order + "HHiIII", _read_exact(stream, 20, "pcap header"))
    while record := stream.read(16):
        if len(record) < 16:
            raise PcapFormatError("truncated record header")
        seconds, fraction, captured, _ = struct.unpack(order + "IIII", record)
        data = _read_exact(stream, captured, "record")
        yield CapturedFrame(seconds + fraction / fraction_per_s, link_type, data)


def _read_pcapng(stream: BinaryIO, first: bytes) -> Iterator[CapturedFrame]:
    order = "<"
    interfaces: list[tuple[int, float]] = []
    block_type_bytes = first
    while True:
        length_bytes = _read_exact(stream, 4, "block length")
        if struct.unpack("<I", block_type_bytes)[0] == _PCAPNG_SECTION_HEADER:
            magic = _read_exact(stream, 4, "byte-order magic")
            order = "<" if struct.unpack("<I", magic)[0] == _PCAPNG_BYTE_ORDER_MAGIC else ">"
            (length,) = struct.unpack(order + "I", length_bytes)
            if length < 16:
                raise PcapFormatError("section header block too short")
            _read_exact(stream, length - 12, "section header block")
            interfaces = []
        else:
            (block_type,) = struct.unpack(order + "I", block_type_bytes)
            (length,) = struct.unpack(order + "I", length_bytes)
            if length < 12:
                raise PcapFormatError(f"block of {length} bytes")
            body = _read_exact(stream, length - 12, "block body")
            _read_exact(stream, 4, "block trailer")
            frame = _pcapng_block(block_type, body, order, interfaces)
            if frame is not None:
                yield frame
        block_type_bytes = stream.read(4)
        if not block_type_bytes:
            return
        if len(block_type_bytes) < 4:
            raise PcapFormatError("truncated block type")


def _pcapng_block(block_type: int, body: bytes, order: str,
                  interfaces: list[tuple[int, float]]) -> CapturedFrame | None:
    if block_type == _PCAPNG_INTERFACE_DESCRIPTION:
        if len(body) < 8:
            raise PcapFormatError("interface description block too short")
        link_type = struct.unpack_from(order + "H", body)[0]
        interfaces.append((link_type, _tick_s(body[8:], order)))
    elif block_type == _PCAPNG_ENHANCED_PACKET:
        if len(body) < 20:
            raise PcapFormatError("enhanced packet block too short")
        interface, high, low, captured, _ = struct.unpack_from(order + "IIIII", body)
        if interface >= len(interfaces):
            raise PcapFormatError(f"packet on undeclared interface {interface}")
        link_type, tick_s = interfaces[interface]
        return CapturedFrame(((high << 32) | low) * tick_s, link_type, body[20:20 + captured])
    elif block_type == _PCAPNG_SIMPLE_PACKET:
        if len(body) < 4:
            raise PcapFormatError("simple packet block too short")
        (original,) = struct.unpack_from(order + "I", body)
        link_type = interfaces[0][0] if interfaces else LINKTYPE_ETHERNET
        return CapturedFrame(0.0, link_type, body[4:4 + original])
    return None


def _tick_s(options: bytes, order: str) -> float:
    """Timestamp unit of an interface from its if_tsresol option (default microseconds)."""
    offset, resolution = 0, _DEFAULT_TSRESOL
    while offset + 4 <= len(options):
        code, length = struct.unpack_from(order + "HH", options, offset)
        if code == 0:
            break
        if code == _PCAPNG_IF_TSRESOL and length >= 1:
            resolution = options[offset + 4]
        offset += 4 + length + (-length % 4)
    if resolution & 0x80:
        return 2.0 ** -(resolution & 0x7F)
    return 10.0 ** -resolution
