"""Synthetic remote stations for the v2x service tests: CAM packets at a known rate from a known MAC."""

from __future__ import annotations

from coopdrive.v2x.packet import GnParams, encode_cam
from coopdrive.v2x.timebase import ItsClock, generation_delta_time_ms
from coopdrive.v1 import its_pb2

# 2016-05-28T10:00:00Z, the GCDC weekend: sim time 0 maps to this instant.
EPOCH_UNIX_S = 1_464_429_600.0
CLOCK = ItsClock(EPOCH_UNIX_S)
REMOTE_MAC = bytes.fromhex("02000000002a")
REMOTE_STATION_ID = 2002
LATITUDE_DEG, LONGITUDE_DEG = 51.4758, 5.6247
METRES_PER_DEGREE_LATITUDE = 111_195.0


def remote_cam(generation_s: float, station_id: int = REMOTE_STATION_ID, speed_mps: float = 20.0,
               north_m: float | None = None, accel_mps2: float = 0.0, clock: ItsClock = CLOCK) -> its_pb2.CamContent:
    """A CAM of a car driving north at speed_mps, generated at sim time generation_s."""
    north_m = speed_mps * generation_s if north_m is None else north_m
    content = its_pb2.CamContent(protocol_version=1, station_id=station_id, station_type=5,
                                 generation_delta_time_ms=generation_delta_time_ms(clock.tai_ms(generation_s)))
    content.reference_position.latitude_deg = LATITUDE_DEG + north_m / METRES_PER_DEGREE_LATITUDE
    content.reference_position.longitude_deg = LONGITUDE_DEG
    content.high_frequency.speed_mps = speed_mps
    content.high_frequency.heading_rad = 1.5707963
    content.high_frequency.longitudinal_acceleration_mps2 = accel_mps2
    return content


def cam_packet(content: its_pb2.CamContent, generation_s: float, mac: bytes = REMOTE_MAC, gn_version: int = 0,
               clock: ItsClock = CLOCK) -> bytes:
    return encode_cam(content, GnParams(source_mac=mac, gn_version=gn_version, time_tai_ms=clock.tai_ms(generation_s)))
