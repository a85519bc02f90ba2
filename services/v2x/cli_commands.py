"""What `coopdrive v2x decode` and `coopdrive v2x send` do (the CLI only parses arguments and prints).

    for line in decode_capture("drive.pcap", as_json=False): print(line)
    send_from_yaml("cam.yaml", "127.0.0.1", 4401)

A send file names the message type and gives its content as the protobuf JSON of CamContent, DenmContent
or IclcmContent (field names as in its.proto); GeoNetworking settings are optional:

    type: cam                  # cam | denm | iclcm
    gn: {source_mac: "02:00:00:00:00:2a", gn_version: 0}
    content:
      station_id: 42
      reference_position: {latitude_deg: 51.45, longitude_deg: 5.48}
      high_frequency: {speed_mps: 13.9, heading_rad: 1.57}

A missing generationDeltaTime (CAM, iCLCM) or detection/reference time (DENM) is taken from the clock.
"""

from __future__ import annotations

import enum
import json
import socket
import time
from collections.abc import Iterator
from pathlib import Path

import yaml
from google.protobuf import json_format
from pydantic import BaseModel, ConfigDict, Field

from coopdrive.services.v2x.codec import ItsMessageId
from coopdrive.services.v2x.config import parse_mac
from coopdrive.services.v2x.geonet import GN_VERSION_GCDC
from coopdrive.services.v2x.its_clock import ItsClock
from coopdrive.services.v2x.packet import GnParams, SourcePosition, V2xPacketCodec, default_codec
from coopdrive.services.v2x.capture import read_gn_packets
from coopdrive.services.v2x.reasons import V2xDecodeError
from coopdrive.services.v2x.timebase import generation_delta_time_ms
from coopdrive.v1 import its_pb2


class SendFileError(ValueError):
    """A send file that cannot be turned into a packet; the message names the file and what was wrong."""


class MessageKind(enum.Enum):
    CAM = "cam"
    DENM = "denm"
    ICLCM = "iclcm"


CONTENT_OF_KIND = {MessageKind.CAM: its_pb2.CamContent, MessageKind.DENM: its_pb2.DenmContent,
                   MessageKind.ICLCM: its_pb2.IclcmContent}


class GnSettings(BaseModel):
    model_config = ConfigDict(extra="forbid")

    source_mac: str = "02:00:00:00:00:fe"
    gn_version: int = GN_VERSION_GCDC
    station_type: int = its_pb2.STATION_TYPE_PASSENGER_CAR
    lifetime_s: float = Field(1.0, gt=0.0)


class SendFile(BaseModel):
    model_config = ConfigDict(extra="forbid")

    type: MessageKind
    gn: GnSettings = GnSettings()
    content: dict = Field(default_factory=dict)


def _format_mac(mac: bytes | None) -> str:
    return ":".join(f"{byte:02x}" for byte in mac) if mac else "-"


def decode_capture(path: str | Path, as_json: bool = False,
                   codec: V2xPacketCodec | None = None) -> Iterator[str]:
    """One line per GeoNetworking packet of a pcap or pcapng file: a summary, or a JSON object.

    Undecodable packets give a line with the reject reason, so a capture never stops the listing.
    """
    codec = codec or default_codec()
    with open(path, "rb") as stream:
        for index, captured in enumerate(read_gn_packets(stream)):
            record = {"index": index, "time_s": captured.time_s, "source_mac": _format_mac(captured.source_mac)}
            try:
                decoded = codec.decode_packet(captured.gn_packet)
            except V2xDecodeError as error:
                record["error"] = error.reason.value
                record["detail"] = error.detail
            else:
                record["message_type"] = decoded.message_type.name
                record["station_id"] = decoded.station_id
                record["gn_version"] = decoded.gn.basic.version
                record["content"] = json_format.MessageToDict(decoded.content, preserving_proto_field_name=True)
            yield json.dumps(record, sort_keys=True) if as_json else _summary(record)


def _summary(record: dict) -> str:
    head = f"{record['index']:6d} {record['time_s']:.6f} {record['source_mac']}"
    if "error" in record:
        return f"{head} REJECTED {record['error']} {record['detail']}".rstrip()
    content = record["content"]
    text = f"{head} GNv{record['gn_version']} {record['message_type']} station {record['station_id']}"
    position = content.get("reference_position") or content.get("event_position") or {}
    if "latitude_deg" in position and "longitude_deg" in position:
        text += f" at {position['latitude_deg']:.7f},{position['longitude_deg']:.7f}"
    speed = content.get("high_frequency", {}).get("speed_mps")
    if speed is not None:
        text += f" {speed:.2f} m/s"
    return text


def load_send_file(path: str | Path) -> SendFile:
    try:
        document = yaml.safe_load(Path(path).read_text())
        return SendFile.model_validate(document)
    except (OSError, yaml.YAMLError, ValueError) as error:
        raise SendFileError(f"{path}: {error}") from None


def packet_from_send_file(send: SendFile, unix_s: float, codec: V2xPacketCodec | None = None) -> bytes:
    """The GN packet a send file describes, its missing times taken from unix_s."""
    codec = codec or default_codec()
    try:
        content = json_format.ParseDict(send.content, CONTENT_OF_KIND[send.type]())
        mac = parse_mac(send.gn.source_mac)
    except (json_format.ParseError, ValueError) as error:
        raise SendFileError(f"{send.type.value} content: {error}") from None
    tai_ms = ItsClock().tai_ms(unix_s)
    params = GnParams(source_mac=mac, station_type=send.gn.station_type, gn_version=send.gn.gn_version,
                      lifetime_s=send.gn.lifetime_s, time_tai_ms=tai_ms)
    if send.type is MessageKind.DENM:
        content.detection_time_tai_ms = content.detection_time_tai_ms or tai_ms
        content.reference_time_tai_ms = content.reference_time_tai_ms or tai_ms
        params.source_position = SourcePosition(content.event_position.latitude_deg,
                                                content.event_position.longitude_deg)
    elif "generation_delta_time_ms" not in send.content:
        content.generation_delta_time_ms = generation_delta_time_ms(tai_ms)
    if send.type is MessageKind.ICLCM:
        content.protocol_version = content.protocol_version or 1
        params.source_position = SourcePosition(0.0, 0.0, position_accurate=False)
    elif not content.protocol_version:
        content.protocol_version = 1
    encode = {MessageKind.CAM: codec.encode_cam, MessageKind.DENM: codec.encode_denm,
              MessageKind.ICLCM: codec.encode_iclcm}[send.type]
    try:
        return encode(content, params)
    except (ValueError, KeyError, TypeError) as error:
        raise SendFileError(f"{send.type.value} cannot be encoded: {error}") from None


def send_from_yaml(path: str | Path, address: str = "127.0.0.1", port: int = 4401) -> ItsMessageId:
    """Injects the one CAM, DENM or iCLCM described in the YAML file as a UDP datagram; returns its type."""
    send = load_send_file(path)
    packet = packet_from_send_file(send, time.time())
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sender:
        sender.sendto(packet, (address, port))
    return ItsMessageId[send.type.name]
