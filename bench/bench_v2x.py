"""V2X codec throughput: the full GeoNetworking + BTP + ASN.1 + protobuf path against bare asn1tools.

    python bench/bench_v2x.py [--seconds 1.0]     (or BENCH_V2X_SECONDS=1.0 python -m bench v2x)
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable

from coopdrive.services.v2x.codec import ItsCodec, ItsMessageId, PDU_TYPE_NAMES
from coopdrive.services.v2x.mapping.cam import cam_to_asn
from coopdrive.services.v2x.mapping.iclcm import iclcm_to_asn
from coopdrive.services.v2x.packet import GnParams, SourcePosition, V2xPacketCodec
from coopdrive.v1 import its_pb2

GN = GnParams(source_mac=bytes.fromhex("020000000001"), time_tai_ms=391_478_404_000,
              source_position=SourcePosition(57.7089, 11.9735, 22.2, 0.3))


def typical_cam() -> its_pb2.CamContent:
    """A GCDC-style 25 Hz CAM: basic and high-frequency containers, no low-frequency one."""
    content = its_pb2.CamContent(protocol_version=1, station_id=1001, generation_delta_time_ms=40_000,
                                 station_type=its_pb2.STATION_TYPE_PASSENGER_CAR)
    position = content.reference_position
    position.latitude_deg, position.longitude_deg, position.altitude_m = 57.7089, 11.9735, 12.0
    position.semi_major_confidence_m, position.semi_minor_confidence_m = 0.5, 0.3
    hf = content.high_frequency
    hf.heading_rad, hf.speed_mps, hf.vehicle_length_m, hf.vehicle_width_m = 0.3, 22.2, 4.5, 1.8
    hf.longitudinal_acceleration_mps2, hf.curvature_per_m, hf.yaw_rate_radps = -0.4, 0.001, 0.02
    hf.drive_direction = its_pb2.DRIVE_DIRECTION_FORWARD
    return content


def typical_iclcm() -> its_pb2.IclcmContent:
    return its_pb2.IclcmContent(
        protocol_version=1, station_id=1001, generation_delta_time_ms=40_000, rear_axle_location_m=3.5,
        controller_type=its_pb2.CONTROLLER_TYPE_CACC, response_time_constant_s=0.5, response_time_delay_s=0.2,
        target_longitudinal_acceleration_mps2=0.3, time_headway_s=0.5, cruise_speed_mps=22.2, mio_id=1002,
        mio_range_m=12.0, mio_bearing_rad=0.01, mio_range_rate_mps=-0.2, lane=2, forward_id=1002, backward_id=1000,
        platoon_id=1, distance_travelled_cz_m=0.0, intention=its_pb2.INTENTION_STRAIGHT)


def rate_per_s(operation: Callable[[], object], seconds: float) -> float:
    operation()
    count, start = 0, time.perf_counter()
    deadline = start + seconds
    while True:
        for _ in range(100):
            operation()
        count += 100
        now = time.perf_counter()
        if now >= deadline:
            return count / (now - start)


def main(argv: list[str] | None = None) -> None:
    """argv None: the time per measurement comes from BENCH_V2X_SECONDS, since `python -m bench NAME` puts
    the bench's name on the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=float(os.environ.get("BENCH_V2X_SECONDS", 1.0)),
                        help="time per measurement")
    seconds = parser.parse_args(argv if argv is not None else []).seconds
    packet_codec = V2xPacketCodec()
    spec = packet_codec.its_codec.spec(1)
    cases = [
        ("CAM", ItsMessageId.CAM, typical_cam(), packet_codec.encode_cam, cam_to_asn),
        ("iCLCM", ItsMessageId.ICLCM, typical_iclcm(), packet_codec.encode_iclcm, iclcm_to_asn),
    ]
    print(f"{'message':8} {'path':26} {'bytes':>6} {'encode/s':>10} {'decode/s':>10}")
    for name, message_id, content, encode, to_asn in cases:
        packet, value = encode(content, GN), to_asn(content)
        uper = spec.encode(PDU_TYPE_NAMES[message_id], value)
        rows = [
            ("GN+BTP+UPER+protobuf", len(packet), lambda: encode(content, GN),
             lambda: packet_codec.decode_packet(packet)),
            ("bare asn1tools UPER", len(uper), lambda: spec.encode(PDU_TYPE_NAMES[message_id], value),
             lambda: spec.decode(PDU_TYPE_NAMES[message_id], uper)),
        ]
        for path, size, encode_once, decode_once in rows:
            print(f"{name:8} {path:26} {size:6d} {rate_per_s(encode_once, seconds):10.0f} "
                  f"{rate_per_s(decode_once, seconds):10.0f}")
    start = time.perf_counter()
    ItsCodec().spec(1)
    print(f"\nschema v1 load from the disk cache: {1000 * (time.perf_counter() - start):.0f} ms")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
