"""Signed packets shared by the security tests: a CAM, a DENM and an iCLCM from one test PKI per curve."""

import time

from coopdrive.v2x.packet import GnParams, SourcePosition, V2xPacketCodec
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.timebase import tai_ms_from_unix_s
from coopdrive.v1 import its_pb2

from ..messages import denm, iclcm

US_PER_MS = 1000
LATITUDE_DEG, LONGITUDE_DEG = 57.7089, 11.9735
CODEC = V2xPacketCodec()


def now_tai_us() -> int:
    return tai_ms_from_unix_s(time.time()) * US_PER_MS


def cam(station_id: int, speed_mps: float = 22.2) -> its_pb2.CamContent:
    content = its_pb2.CamContent(protocol_version=1, station_id=station_id, station_type=5)
    content.reference_position.latitude_deg = LATITUDE_DEG
    content.reference_position.longitude_deg = LONGITUDE_DEG
    content.high_frequency.speed_mps = speed_mps
    content.high_frequency.heading_rad = 0.3
    return content


def gn_params(signer: SecuredPacketSigner, gn_version: int = 1) -> GnParams:
    return GnParams(source_mac=signer.mac, gn_version=gn_version,
                    source_position=SourcePosition(LATITUDE_DEG, LONGITUDE_DEG, 22.2, 0.3))


def cam_packet(signer: SecuredPacketSigner, gn_version: int = 1) -> bytes:
    return CODEC.encode_cam(cam(signer.station_id), gn_params(signer, gn_version))


def denm_packet(signer: SecuredPacketSigner) -> bytes:
    content = denm(False, 1)
    content.station_id = signer.station_id
    return CODEC.encode_denm(content, gn_params(signer))


def iclcm_packet(signer: SecuredPacketSigner) -> bytes:
    content = iclcm(False)
    content.station_id = signer.station_id
    return CODEC.encode_iclcm(content, gn_params(signer))
