"""What `coopdrive v2x send FILE` does: one CAM, DENM or iCLCM described in YAML, encoded and sent as UDP.

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
import socket
import time
from pathlib import Path

import yaml
from google.protobuf import json_format
from pydantic import BaseModel, ConfigDict, Field

from coopdrive.services.v2x.config import parse_mac
from coopdrive.v2x.geonet import GN_VERSION_GCDC
from coopdrive.v2x.its_pdu import ItsMessageId
from coopdrive.v2x.packet import GnParams, SourcePosition, V2xPacketCodec, default_codec
from coopdrive.v2x.timebase import ItsClock, generation_delta_time_ms
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
