"""V2X codec throughput: the GeoNetworking + BTP + ASN.1 path, with and without the mapping to protobuf
content, against bare asn1tools encoding and decoding the same UPER payloads.

    python bench/bench_v2x.py [--seconds 1.0]     (or BENCH_V2X_SECONDS=1.0 python -m bench v2x)
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from dataclasses import dataclass

from bench.figure import Better, Figure, Unit, instruction_ratio, ratio
from bench.instructions_per_call import Workload, per_call
from bench.sizes import sized
from bench.turn_about import best_rates_per_s
from coopdrive.v1 import its_pb2
from coopdrive.v2x.its_pdu import PDU_TYPE_NAMES, ItsCodec, ItsMessageId
from coopdrive.v2x.mapping.cam import cam_to_asn
from coopdrive.v2x.mapping.iclcm import iclcm_to_asn
from coopdrive.v2x.packet import GnParams, SourcePosition, V2xPacketCodec

BARE = "bare asn1tools UPER"
# Turns of the five operations of a message within its time (bench/turn_about.py).
ROUNDS = sized(10, 1)
STATIONS = 100
RATE_HZ = 25.0
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


@dataclass
class Row:
    message: str
    path: str
    size_bytes: int
    encode_per_s: float | None
    decode_per_s: float


# Calls of each operation whose instructions are counted (the same input each time).
INSTRUCTION_CALLS = 200
INSTRUCTION_WORKLOADS = "bench.bench_v2x:instruction_workloads"


@dataclass(frozen=True)
class MessageOperations:
    """One typical message's five operations: bare asn1tools' encode and decode of its UPER payload, our decode of
    the GeoNetworking frame, and our encode and decode of the whole packet to and from protobuf content."""
    message: str
    uper_bytes: int
    packet_bytes: int
    calls: tuple[Callable[[], object], ...]

    NAMES = ("bare encode", "bare decode", "frame decode", "full encode", "full decode")
    # Each table row's path, as the operations name it.
    PATHS = {BARE: "bare", "GN+BTP+UPER": "frame", "GN+BTP+UPER+protobuf": "full"}


def operations() -> list[MessageOperations]:
    packet_codec = V2xPacketCodec()
    spec = packet_codec.its_codec.spec(1)
    cases = [
        ("CAM", ItsMessageId.CAM, typical_cam(), packet_codec.encode_cam, cam_to_asn),
        ("iCLCM", ItsMessageId.ICLCM, typical_iclcm(), packet_codec.encode_iclcm, iclcm_to_asn),
    ]
    messages = []
    for name, message_id, content, encode, to_asn in cases:
        packet, value, type_name = encode(content, GN), to_asn(content), PDU_TYPE_NAMES[message_id]
        uper = spec.encode(type_name, value)
        messages.append(MessageOperations(name, len(uper), len(packet), (
            lambda t=type_name, v=value: spec.encode(t, v), lambda t=type_name, u=uper: spec.decode(t, u),
            lambda p=packet: packet_codec.decode_frame(p), lambda c=content, e=encode: e(c, GN),
            lambda p=packet: packet_codec.decode_packet(p))))
    return messages


def instruction_workloads() -> list[Workload]:
    return [Workload(f"{message.message} {operation}", [call] * INSTRUCTION_CALLS)
            for message in operations() for operation, call in zip(MessageOperations.NAMES, message.calls)]


def measure(seconds: float) -> list[Row]:
    rows = []
    for message in operations():
        # The five operations of a message turn about, so each ratio's sides share the machine's load alike.
        bare_encode, bare_decode, frame_decode, full_encode, full_decode = best_rates_per_s(
            message.calls, 5 * seconds, ROUNDS)
        rows += [Row(message.message, BARE, message.uper_bytes, bare_encode, bare_decode),
                 Row(message.message, "GN+BTP+UPER", message.packet_bytes, None, frame_decode),
                 Row(message.message, "GN+BTP+UPER+protobuf", message.packet_bytes, full_encode, full_decode)]
    return rows


def _times_bare(rate: float | None, bare_rate: float | None) -> str:
    return "-" if rate is None or bare_rate is None else f"{bare_rate / rate:.2f}"


def main(argv: list[str] | None = None) -> list[Figure]:
    """argv None: the time per measurement comes from BENCH_V2X_SECONDS, since `python -m bench NAME` puts
    the bench's name on the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=float(os.environ.get("BENCH_V2X_SECONDS", sized(1.0, 0.05))),
                        help="time per measurement")
    seconds = parser.parse_args(argv if argv is not None else []).seconds
    instructions = per_call(INSTRUCTION_WORKLOADS)
    rows = measure(seconds)
    bare = {row.message: row for row in rows if row.path == BARE}
    print(f"{'message':8} {'path':22} {'bytes':>5} {'encode/s':>9} {'decode/s':>9} {'encode x bare':>13} "
          f"{'decode x bare':>13}")
    figures = []
    for row in rows:
        encode = "-" if row.encode_per_s is None else f"{row.encode_per_s:9.0f}"
        print(f"{row.message:8} {row.path:22} {row.size_bytes:5d} {encode:>9} {row.decode_per_s:9.0f} "
              f"{_times_bare(row.encode_per_s, bare[row.message].encode_per_s):>13} "
              f"{_times_bare(row.decode_per_s, bare[row.message].decode_per_s):>13}")
        figures += row_figures(row, bare[row.message], instructions)
    full = [row for row in rows if row.path == "GN+BTP+UPER+protobuf"]
    core_share = sum(STATIONS * RATE_HZ / row.decode_per_s for row in full)
    print(f"\n{STATIONS} stations sending CAM and iCLCM at {RATE_HZ:.0f} Hz each: decoding them to protobuf takes "
          f"{100 * core_share:.0f}% of one core")
    start = time.perf_counter()
    ItsCodec().spec(1)
    load_ms = 1000 * (time.perf_counter() - start)
    print(f"schema v1 load from the disk cache: {load_ms:.0f} ms")
    return figures + [Figure("schema v1 load from the disk cache", load_ms, Unit.MS)]


def row_figures(row: Row, bare: Row, instructions: dict[str, float] | None) -> list[Figure]:
    """A row's rates, and beside the bare row's its time per message as a multiple of bare asn1tools', guarded by
    the same multiple in instructions where they were counted."""
    figures = []
    for operation, rate, bare_rate in (("encode", row.encode_per_s, bare.encode_per_s),
                                       ("decode", row.decode_per_s, bare.decode_per_s)):
        if rate is None:
            continue
        figures.append(Figure(f"{row.message} {row.path} {operation}s", rate, Unit.PER_S))
        if row is bare:
            continue
        name, baseline = f"{row.message} {row.path} {operation}: time x bare", f"{row.message} {BARE} {operation}s"
        counted = None if instructions is None else instruction_ratio(
            name, instructions[f"{row.message} {MessageOperations.PATHS[row.path]} {operation}"]
            / instructions[f"{row.message} bare {operation}"], baseline)
        figures += ([] if counted is None else [counted]) + [
            ratio(name, bare_rate / rate, baseline, Better.LOWER, guarded_by=None if counted is None else counted.name)]
    return figures


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
