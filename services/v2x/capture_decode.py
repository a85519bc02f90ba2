"""What `coopdrive v2x decode FILE` does: every frame of a real capture, decoded as far as it goes, and a summary.

    for line in decode_capture("drive.pcapng", as_json=False, trust=[Path("eu-roots/")]): print(line)
    # or, record by record:
    decoder = CaptureDecoder(trust_store(["eu-roots/"]), freshness=True)
    for record in decoder.records("drive.pcapng"):     # one dict per frame, JSON-ready
        print(format_record(record))                   # or json.dumps(record)
    print(format_summary(decoder.summary))             # decoder.summary.as_dict() for JSON

A record: index, time_s, link_type, source_mac, ethertype; `unreadable` (+ detail) for frames that carry no
GeoNetworking; otherwise `gn` (version, header_type, station_type, position), message_type (`beacon`, or by
BTP port: `cam`, `denm`, `iclcm`, `spatem`, `mapem`, `ivim`, `srem`, `ssem`, `cpm`, `vam`, ..., `btp_<port>`),
btp_port, station_id, `content` for the types we decode (CAM/DENM/iCLCM and SPATEM/MAPEM/SREM/SSEM in SI units as
protobuf JSON, CPM/VAM as ASN.1 values),
`error` (+ detail) when that failed, and `security` (security.inspection.SecurityResult.as_dict()).
Freshness is judged against the capture time of each frame (freshness=False: not judged).
"""

from __future__ import annotations

import json
import struct
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import BinaryIO

from google.protobuf import json_format

from coopdrive.v2x.btp import MESSAGE_NAME_OF_PORT, parse_btp_b
from coopdrive.recording.capture import CapturedFrame, read_capture
from coopdrive.services.v2x.capture_summary import DecodeSummary, format_summary
from coopdrive.v2x.geonet import BeaconHeader, CommonNextHeader, GnPacket, HeaderType, parse_gn
from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.reasons import V2xDecodeError
from coopdrive.v2x.release2 import TOP_TYPE_OF_MESSAGE, release2_content
from coopdrive.v2x.security.inspection import PacketInspector
from coopdrive.v2x.security.store import CertificateStore
from coopdrive.v2x.security.trust import trust_store
from coopdrive.v2x.timebase import US_PER_MS, tai_ms_from_unix_s
from coopdrive.v2x.units import TENTH_MICRODEG_PER_DEG

MAPPED_MESSAGES = ("cam", "denm", "iclcm", "spatem", "mapem", "srem", "ssem")
HEADER_TYPE_NAMES = {HeaderType.BEACON: "beacon", HeaderType.TOPOLOGICALLY_SCOPED_BROADCAST: "tsb_single_hop",
                     HeaderType.GEOBROADCAST: "geobroadcast"}
# ItsPduHeader in UPER: protocolVersion and messageID (8 bits each), stationID (32 bits), octet-aligned.
_ITS_PDU_HEADER = struct.Struct(">BBI")
DECODE_FAILED = "decode_failed"


def format_mac(mac: bytes | None) -> str | None:
    return ":".join(f"{byte:02x}" for byte in mac) if mac else None


class CaptureDecoder:
    def __init__(self, store: CertificateStore | None = None, freshness: bool = True,
                 codec: V2xPacketCodec | None = None):
        self.inspector = PacketInspector(store or CertificateStore())
        self.freshness = freshness
        self.codec = codec or V2xPacketCodec()
        self.summary = DecodeSummary()

    def records(self, source: str | Path | BinaryIO) -> Iterator[dict]:
        """One record per frame, in file order (CaptureFormatError when the file is no capture)."""
        for frame in read_capture(source):
            record = self.record(frame)
            self.summary.add(record)
            yield record

    def record(self, frame: CapturedFrame) -> dict:
        record = {"index": frame.index, "time_s": frame.time_s, "link_type": frame.link_type,
                  "source_mac": format_mac(frame.source_mac),
                  "ethertype": f"0x{frame.ethertype:04x}" if frame.ethertype is not None else None}
        if frame.gn_packet is None:
            return {**record, "unreadable": frame.unreadable, "detail": frame.detail}
        now_tai_us = tai_ms_from_unix_s(frame.time_s) * US_PER_MS if self.freshness else None
        inspected = self.inspector.inspect(frame.gn_packet, now_tai_us)
        record["security"] = inspected.security.as_dict()
        if inspected.unsecured_packet is None:
            return {**record, "error": inspected.security.reason.value, "detail": "security envelope"}
        try:
            gn = parse_gn(inspected.unsecured_packet)
        except V2xDecodeError as error:
            return {**record, "error": error.reason.value, "detail": error.detail}
        record["gn"] = _gn_record(gn)
        record.update(self._message(gn, inspected.unsecured_packet))
        return record

    def _message(self, gn: GnPacket, unsecured: bytes) -> dict:
        if isinstance(gn.extended, BeaconHeader):
            return {"message_type": "beacon", "station_id": None}
        if gn.common.next_header not in (CommonNextHeader.BTP_A, CommonNextHeader.BTP_B):
            return {"message_type": None, "error": "not_btp", "detail": gn.common.next_header.name}
        try:
            btp, payload = parse_btp_b(gn.payload)
        except V2xDecodeError as error:
            return {"message_type": None, "error": error.reason.value, "detail": error.detail}
        port = btp.destination_port
        message = MESSAGE_NAME_OF_PORT.get(port, f"btp_{port}")
        record = {"message_type": message, "btp_port": port, "station_id": _station_id(payload)}
        try:
            record.update(self._content(message, unsecured, payload))
        except V2xDecodeError as error:
            record.update(error=error.reason.value, detail=error.detail)
        except Exception as error:  # noqa: BLE001 -- asn1tools raises many types on bad UPER
            record.update(error=DECODE_FAILED, detail=f"{type(error).__name__}: {error}")
        return record

    def _content(self, message: str, unsecured: bytes, payload: bytes) -> dict:
        if message in MAPPED_MESSAGES:
            decoded = self.codec.decode_packet(unsecured)
            return {"station_id": decoded.station_id,
                    "content": json_format.MessageToDict(decoded.content, preserving_proto_field_name=True)}
        if message in TOP_TYPE_OF_MESSAGE:
            return {"content": release2_content(message, payload)}
        return {}


def _station_id(its_pdu: bytes) -> int | None:
    if len(its_pdu) < _ITS_PDU_HEADER.size:
        return None
    return _ITS_PDU_HEADER.unpack_from(its_pdu)[2]


def _gn_record(gn: GnPacket) -> dict:
    position = gn.extended.source_position
    return {"version": gn.basic.version,
            "header_type": HEADER_TYPE_NAMES.get(gn.common.header_type, gn.common.header_type.name.lower()),
            "station_type": position.address.station_type, "gn_address_mac": format_mac(position.address.mid),
            "latitude_deg": position.latitude_tenth_microdeg / TENTH_MICRODEG_PER_DEG,
            "longitude_deg": position.longitude_tenth_microdeg / TENTH_MICRODEG_PER_DEG}


def decode_capture(path: str | Path, as_json: bool = False, trust: Sequence[Path] = (),
                   freshness: bool = True) -> Iterator[str]:
    """One line (or JSON object) per frame of a pcap or pcapng file, then the summary.

    Frames that cannot be read or decoded give a line with the reason, so a capture never stops the listing.
    trust: certificate files or directories (security/trust.py); freshness against the capture's timestamps.
    """
    decoder = CaptureDecoder(trust_store(trust) if trust else None, freshness=freshness)
    for record in decoder.records(path):
        yield json.dumps(record, sort_keys=True) if as_json else format_record(record)
    if as_json:
        yield json.dumps({"summary": decoder.summary.as_dict()}, sort_keys=True)
    else:
        yield from format_summary(decoder.summary)


def format_record(record: dict) -> str:
    """One line per frame, for people."""
    head = f"{record['index']:6d} {record['time_s']:.6f} {record['link_type']} {record['source_mac'] or '-'}"
    if "unreadable" in record:
        return f"{head} UNREADABLE {record['unreadable']} {record['detail']}".rstrip()
    gn = record.get("gn")
    text = head + (f" GNv{gn['version']} {gn['header_type']}" if gn else "")
    if record.get("message_type"):
        text += f" {record['message_type']}"
    if record.get("station_id") is not None:
        text += f" station {record['station_id']}"
    text += _content_text(record.get("content") or {})
    if "error" in record:
        text += f" ERROR {record['error']} {record['detail']}".rstrip()
    return text + _security_text(record.get("security"))


def _content_text(content: dict) -> str:
    text = ""
    position = content.get("reference_position") or content.get("event_position") or {}
    if "latitude_deg" in position and "longitude_deg" in position:
        text += f" at {position['latitude_deg']:.7f},{position['longitude_deg']:.7f}"
    speed = content.get("high_frequency", {}).get("speed_mps")
    if speed is not None:
        text += f" {speed:.2f} m/s"
    for intersection in content.get("intersections", ()):
        if "id" in intersection:  # SPATEM and MAPEM; an SSEM's intersections name theirs `intersection`
            text += _intersection_text(intersection)
    return text


def _intersection_text(intersection: dict) -> str:
    """A MAPEM's intersection with its lane count, a SPATEM's with each signal group's current phase."""
    text = f" intersection {intersection['id'].get('id', 0)}"
    if "lanes" in intersection:
        text += f": {len(intersection['lanes'])} lanes"
    groups = intersection.get("signal_groups", ())
    if groups and isinstance(groups[0], dict):
        phases = (f"{group.get('signal_group', 0)}={_phase(group)}" for group in groups)
        text += ": " + " ".join(phases)
    return text


def _phase(group: dict) -> str:
    events = group.get("events") or [{}]
    return events[0].get("state", "MOVEMENT_PHASE_STATE_UNAVAILABLE").removeprefix("MOVEMENT_PHASE_STATE_").lower()


def _security_text(security: dict | None) -> str:
    if not security or not security["signed"]:
        return ""
    text = f" signed by {security['signer']} {security['signer_digest']} verified={security['verified']}"
    text += f" trusted={security['trusted']}"
    if security["fresh"] is not None:
        text += f" fresh={security['fresh']}"
    return text + (f" ({security['reason']})" if security["reason"] else "")

