"""A V2X capture (pcap or pcapng of any link type real captures use) as v2x/rx GnPacket messages at the
capture's times, read by the capture reader (coopdrive/recording/capture.py, dpkt).

Frames that carry no GeoNetworking are counted, never silently dropped: other traffic on the link (another
ethertype, 802.11 management frames) as notes, frames that cannot be read as bad.
"""

from __future__ import annotations

from pathlib import Path

from coopdrive.recording.import_source import ImportFailure, SourceReport, TimedMessage
from coopdrive.recording.capture import NOT_A_DATA_FRAME, OTHER_ETHERTYPE, CaptureFormatError, read_capture
from coopdrive.v1 import v2x_pb2

TOPIC = "v2x/rx"
# Frames that are not wrong, only not GeoNetworking.
_OTHER_TRAFFIC = frozenset({OTHER_ETHERTYPE, NOT_A_DATA_FRAME})


def read_pcap(path: Path) -> SourceReport:
    report = SourceReport("pcap", path)
    try:
        for frame in read_capture(path):
            report.items_read += 1
            if frame.gn_packet is None:
                (report.notes if frame.unreadable in _OTHER_TRAFFIC else report.bad)[frame.unreadable] += 1
                continue
            message = v2x_pb2.GnPacket(direction=v2x_pb2.PACKET_DIRECTION_RECEIVED, payload=frame.gn_packet,
                                       source_mac=frame.source_mac or b"")
            report.messages.append(TimedMessage(frame.time_s, TOPIC, message))
    except CaptureFormatError as error:
        raise ImportFailure(f"{path}: not a pcap or pcapng capture ({error})") from None
    return report
