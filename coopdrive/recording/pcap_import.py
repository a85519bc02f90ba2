"""A V2X capture (pcap or pcapng, read with dpkt) as v2x/rx GnPacket messages at the capture's times.

A minimal reader of its own: Ethernet II, Linux cooked captures (SLL, SLL2) and bare GeoNetworking (USER0)
carrying ethertype 0x8947. It is meant to give way to the V2X service's capture reader (services/v2x/) once
that reads the radio link types too (802.11 with radiotap and LLC/SNAP); until then those are counted as
unsupported link types, per type, never silently dropped.
"""

from __future__ import annotations

from pathlib import Path

import dpkt

from coopdrive.recording.import_source import ImportFailure, SourceReport, TimedMessage
from coopdrive.v1 import v2x_pb2

TOPIC = "v2x/rx"
ETHERTYPE_GEONETWORKING = 0x8947
PCAPNG_MAGIC = b"\x0a\x0d\x0d\x0a"
LINKTYPE_ETHERNET = 1
LINKTYPE_LINUX_SLL = 113
LINKTYPE_USER0_BARE_GN = 147
LINKTYPE_LINUX_SLL2 = 276


def read_capture(path: Path) -> SourceReport:
    report = SourceReport("pcap", path)
    with open(path, "rb") as stream:
        magic = stream.read(4)
        stream.seek(0)
        try:
            reader = dpkt.pcapng.Reader(stream) if magic == PCAPNG_MAGIC else dpkt.pcap.Reader(stream)
        except (ValueError, dpkt.dpkt.NeedData, dpkt.dpkt.UnpackError) as error:
            raise ImportFailure(f"{path}: not a pcap or pcapng capture ({error})") from None
        link_type = reader.datalink()
        try:
            for time_s, frame in reader:
                report.items_read += 1
                _read_frame(report, link_type, float(time_s), bytes(frame))
        except (ValueError, dpkt.dpkt.NeedData, dpkt.dpkt.UnpackError):
            report.bad["truncated_capture"] += 1  # the packets before the cut are kept
    return report


def _read_frame(report: SourceReport, link_type: int, time_s: float, frame: bytes) -> None:
    try:
        packet, source_mac, reason = _geonetworking_of(link_type, frame)
    except (dpkt.dpkt.NeedData, dpkt.dpkt.UnpackError, ValueError):
        packet, source_mac, reason = None, b"", "malformed_frame"
    if packet is None:
        # Other traffic on the capture's link is not wrong, only not ours.
        (report.notes if reason == "not_geonetworking" else report.bad)[reason] += 1
        return
    message = v2x_pb2.GnPacket(direction=v2x_pb2.PACKET_DIRECTION_RECEIVED, payload=packet, source_mac=source_mac)
    report.messages.append(TimedMessage(time_s, TOPIC, message))


def _geonetworking_of(link_type: int, frame: bytes) -> tuple[bytes | None, bytes, str]:
    """(GN packet, source MAC, "") or (None, b"", why not)."""
    if link_type == LINKTYPE_USER0_BARE_GN:
        return frame, b"", ""
    if link_type == LINKTYPE_ETHERNET:
        ethernet = dpkt.ethernet.Ethernet(frame)
        ethertype, payload, source = ethernet.type, ethernet.data, ethernet.src
    elif link_type == LINKTYPE_LINUX_SLL:
        cooked = dpkt.sll.SLL(frame)
        ethertype, payload, source = cooked.ethtype, cooked.data, cooked.hdr[:6] if cooked.hlen == 6 else b""
    elif link_type == LINKTYPE_LINUX_SLL2:
        cooked = dpkt.sll2.SLL2(frame)
        ethertype, payload, source = cooked.ethtype, cooked.data, cooked.hdr[:6] if cooked.hlen == 6 else b""
    else:
        return None, b"", f"unsupported_link_type_{link_type}"
    if ethertype != ETHERTYPE_GEONETWORKING:
        return None, b"", "not_geonetworking"
    return bytes(payload) if not isinstance(payload, bytes) else payload, bytes(source), ""
