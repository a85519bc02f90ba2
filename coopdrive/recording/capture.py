"""Read the GeoNetworking packets of a real capture (pcap or pcapng) with dpkt, whatever its link type.

Contract (used by `coopdrive v2x decode` and `coopdrive v2x replay`):

    for frame in read_capture("drive.pcapng"):        # a path or a binary stream
        frame.index, frame.time_s                      # 0-based frame number in the file; capture time, UNIX s
        frame.link_type                                # "ethernet", "ieee802_11", "radiotap", "linux_sll", ...
        frame.source_mac, frame.ethertype              # bytes | None, int | None (as far as the frame was read)
        frame.gn_packet                                # GeoNetworking bytes (basic header first), or None and
        frame.unreadable, frame.detail                 #   one of UNREADABLE_REASONS and a short detail

    for frame in read_gn_packets(path): ...           # only the frames that carry GeoNetworking

Every frame of the file comes out once, in file order: nothing is dropped silently. A radiotap frame is read as its
Flags field says (radiotap.py): its FCS removed where the capture kept it, a frame that failed its FCS counted as
bad_fcs and not read. A file that is neither
pcap nor pcapng raises CaptureFormatError. Link types: Ethernet (1), 802.11 (105), radiotap + 802.11 (127),
Linux cooked v1 (113) and v2 (276), bare GeoNetworking on USER0 (147, what a UDP radio bridge records).
802.11 data frames carry GeoNetworking behind LLC/SNAP with ethertype 0x8947 (ITS-G5, OCB: no encryption).
dpkt reads one interface per pcapng file: a multi-interface pcapng is read with the first interface's link
type. A record cut short at the end of the file comes out shorter (dpkt gives what is there).
"""

from __future__ import annotations

import struct
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

import dpkt

from coopdrive.recording.link_types import (ETHERTYPE_GEONETWORKING, LINK_TYPE_NAMES, LINKTYPE_ETHERNET,
                                            LINKTYPE_IEEE802_11, LINKTYPE_LINUX_SLL, LINKTYPE_LINUX_SLL2,
                                            LINKTYPE_RADIOTAP, LINKTYPE_USER0_BARE_GN)
from coopdrive.recording.radiotap import FCS_BYTES, RadiotapError, read_radiotap

_PCAPNG_MAGIC = b"\x0a\x0d\x0d\x0a"
_LLC_SNAP = b"\xaa\xaa\x03"
_SNAP_HEADER = struct.Struct(">3sH")  # OUI, ethertype after the 3-byte LLC header
_LLC_SIZE = 3
# 802.11 frame control: type 2 is data; subtypes with bit 2 set carry no data (null, CF-ack/poll only).
_IEEE80211_DATA_TYPE = 2
_IEEE80211_NO_DATA_SUBTYPE_BIT = 0x4
_IEEE80211_QOS_SUBTYPE_BIT = 0x8
_IEEE80211_TO_DS, _IEEE80211_FROM_DS = 0x01, 0x02
# Frame control, duration, three addresses and sequence control.
_IEEE80211_BASE_HEADER_BYTES = 24
_MAC_BYTES = 6
_QOS_CONTROL_BYTES = 2

OTHER_ETHERTYPE = "other_ethertype"
UNSUPPORTED_LINK_TYPE = "unsupported_link_type"
MALFORMED_FRAME = "malformed_frame"
NOT_A_DATA_FRAME = "not_a_data_frame"
PROTECTED_FRAME = "protected_frame"
NOT_LLC_SNAP = "not_llc_snap"
# The radio's own check of the frame failed (radiotap's bad-FCS flag): its bytes cannot be trusted.
BAD_FCS = "bad_fcs"
UNREADABLE_REASONS = (OTHER_ETHERTYPE, UNSUPPORTED_LINK_TYPE, MALFORMED_FRAME, NOT_A_DATA_FRAME,
                      PROTECTED_FRAME, NOT_LLC_SNAP, BAD_FCS)


class CaptureFormatError(ValueError):
    """A file that is neither pcap nor pcapng (or whose file header is cut)."""


@dataclass(frozen=True, slots=True)
class CapturedFrame:
    index: int
    time_s: float
    link_type: str
    source_mac: bytes | None
    ethertype: int | None
    gn_packet: bytes | None
    # None when gn_packet is there; else one of UNREADABLE_REASONS.
    unreadable: str | None = None
    detail: str = ""


class _Unreadable(Exception):
    def __init__(self, reason: str, detail: str = "", source_mac: bytes | None = None, ethertype: int | None = None):
        super().__init__(reason)
        self.reason, self.detail, self.source_mac, self.ethertype = reason, detail, source_mac, ethertype


def read_capture(source: str | Path | BinaryIO) -> Iterator[CapturedFrame]:
    """Every frame of a pcap or pcapng file (path or binary stream), in file order."""
    if isinstance(source, (str, Path)):
        with open(source, "rb") as stream:
            yield from _read_stream(stream)
    else:
        yield from _read_stream(source)


def read_gn_packets(source: str | Path | BinaryIO) -> Iterator[CapturedFrame]:
    """Only the frames that carry a GeoNetworking packet (frame.gn_packet is not None)."""
    return (frame for frame in read_capture(source) if frame.gn_packet is not None)


def link_type_name(link_type: int) -> str:
    return LINK_TYPE_NAMES.get(link_type, f"dlt_{link_type}")


def _open_reader(stream: BinaryIO):
    head = stream.read(4)
    stream.seek(-len(head), 1)
    try:
        return dpkt.pcapng.Reader(stream) if head == _PCAPNG_MAGIC else dpkt.pcap.Reader(stream)
    except (ValueError, dpkt.Error, struct.error) as error:
        raise CaptureFormatError(f"not a pcap or pcapng file ({error})") from None


def _read_stream(stream: BinaryIO) -> Iterator[CapturedFrame]:
    reader = _open_reader(stream)
    link_type = reader.datalink()
    name = link_type_name(link_type)
    parse = _PARSERS.get(link_type)
    for index, (time_s, data) in enumerate(reader):
        if parse is None:
            yield CapturedFrame(index, float(time_s), name, None, None, None, UNSUPPORTED_LINK_TYPE, name)
            continue
        try:
            source_mac, ethertype, payload = parse(bytes(data))
        except _Unreadable as why:
            yield CapturedFrame(index, float(time_s), name, why.source_mac, why.ethertype, None, why.reason,
                                why.detail)
        except (dpkt.Error, struct.error, ValueError, IndexError) as error:
            yield CapturedFrame(index, float(time_s), name, None, None, None, MALFORMED_FRAME,
                                f"{type(error).__name__}: {error}")
        else:
            if ethertype != ETHERTYPE_GEONETWORKING:
                yield CapturedFrame(index, float(time_s), name, source_mac, ethertype, None, OTHER_ETHERTYPE,
                                    f"0x{ethertype:04x}")
            else:
                yield CapturedFrame(index, float(time_s), name, source_mac, ethertype, payload)


Parsed = tuple[bytes | None, int | None, bytes]


def _ethernet(data: bytes) -> Parsed:
    if len(data) < 14:
        raise _Unreadable(MALFORMED_FRAME, f"Ethernet frame of {len(data)} bytes")
    frame = dpkt.ethernet.Ethernet(data)
    # dpkt leaves an ethertype it has no class for as bytes; 802.1Q tags are stripped by dpkt.
    payload = frame.data if isinstance(frame.data, bytes) else bytes(frame.data)
    return bytes(frame.src), frame.type, payload


def _bare_gn(data: bytes) -> Parsed:
    return None, ETHERTYPE_GEONETWORKING, data


def _llc_snap(data: bytes, source_mac: bytes | None) -> Parsed:
    if data[:_LLC_SIZE] != _LLC_SNAP or len(data) < _LLC_SIZE + _SNAP_HEADER.size:
        raise _Unreadable(NOT_LLC_SNAP, data[:_LLC_SIZE].hex(), source_mac)
    _, ethertype = _SNAP_HEADER.unpack_from(data, _LLC_SIZE)
    return source_mac, ethertype, data[_LLC_SIZE + _SNAP_HEADER.size:]


def _ieee80211_frame(frame: dpkt.ieee80211.IEEE80211) -> Parsed:
    if frame.type != _IEEE80211_DATA_TYPE:
        raise _Unreadable(NOT_A_DATA_FRAME, f"802.11 type {frame.type} subtype {frame.subtype}")
    data_frame = frame.data_frame
    source_mac = bytes(getattr(data_frame, "sa", None) or data_frame.src)
    if frame.subtype & _IEEE80211_NO_DATA_SUBTYPE_BIT:
        raise _Unreadable(NOT_A_DATA_FRAME, f"802.11 data subtype {frame.subtype} without data", source_mac)
    if frame.wep:
        raise _Unreadable(PROTECTED_FRAME, "802.11 protected frame", source_mac)
    return _llc_snap(bytes(data_frame.data), source_mac)


def _ieee80211(data: bytes) -> Parsed:
    return _ieee80211_frame(dpkt.ieee80211.IEEE80211(data))


def _radiotap(data: bytes) -> Parsed:
    """The 802.11 frame behind the header, as its Flags field says: without its FCS where the capture kept it,
    unpadded where the driver padded the 802.11 header to 32 bits; a frame whose FCS failed is not read."""
    try:
        header = read_radiotap(data)
    except RadiotapError as error:
        raise _Unreadable(MALFORMED_FRAME, str(error)) from None
    if header.bad_fcs:
        raise _Unreadable(BAD_FCS, "radiotap flags: the frame failed its FCS check")
    frame = data[header.length:len(data) - FCS_BYTES if header.has_fcs else len(data)]
    if header.data_padded:
        frame = _without_header_padding(frame)
    return _ieee80211(frame)


def _without_header_padding(frame: bytes) -> bytes:
    """Removes the bytes that pad a data frame's 802.11 header to a multiple of 4 (radiotap's data-pad flag)."""
    if len(frame) < _IEEE80211_BASE_HEADER_BYTES:
        return frame
    frame_type, flags = (frame[0] >> 2) & 0x3, frame[1]
    if frame_type != _IEEE80211_DATA_TYPE:
        return frame
    header_bytes = _IEEE80211_BASE_HEADER_BYTES
    if flags & _IEEE80211_TO_DS and flags & _IEEE80211_FROM_DS:
        header_bytes += _MAC_BYTES  # the fourth address
    if (frame[0] >> 4) & _IEEE80211_QOS_SUBTYPE_BIT:
        header_bytes += _QOS_CONTROL_BYTES
    padding = -header_bytes % 4
    return frame[:header_bytes] + frame[header_bytes + padding:]


def _cooked(header: dpkt.Packet) -> Parsed:
    """Linux cooked capture v1 / v2: the sender's link-layer address (a MAC on Wi-Fi) and the protocol."""
    payload = header.data if isinstance(header.data, bytes) else bytes(header.data)
    return bytes(header.hdr[:min(header.hlen, 8)]) or None, header.ethtype, payload


def _linux_sll(data: bytes) -> Parsed:
    return _cooked(dpkt.sll.SLL(data))


def _linux_sll2(data: bytes) -> Parsed:
    return _cooked(dpkt.sll2.SLL2(data))


_PARSERS = {LINKTYPE_ETHERNET: _ethernet, LINKTYPE_IEEE802_11: _ieee80211, LINKTYPE_RADIOTAP: _radiotap,
            LINKTYPE_LINUX_SLL: _linux_sll, LINKTYPE_LINUX_SLL2: _linux_sll2, LINKTYPE_USER0_BARE_GN: _bare_gn}
