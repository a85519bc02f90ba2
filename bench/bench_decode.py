"""Decoding received packets on one core: a real signed CAM (unwrap + verify + decode) and an unsigned CAM, our
path against bare asn1tools + cryptography doing the same work.

    python -m bench decode            (BENCH_DECODE_SECONDS=1.0 for the time per measurement)

Like for like: both sides decode the security envelope (OER), hash the to-be-signed bytes and the signer's
certificate, verify the ECDSA signature with a key parsed once, and decode the CAM (UPER). Bare code knows the
byte offsets in advance; ours finds them (GN, BTP, envelope spans), checks the certificate's and signature's
canonical encoding, the PSID against the BTP port, and caches the certificate. The unsigned rows: our whole
decode path (security test, GN + BTP headers, ITS header, UPER) against the same checks written out with struct
followed by asn1tools' decode (like for like), and against asn1tools decoding the UPER alone.
"""

from __future__ import annotations

import hashlib
import os
import struct
from collections.abc import Callable

from cryptography.hazmat.primitives import hashes
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.hazmat.primitives.asymmetric.utils import Prehashed, encode_dss_signature

from bench.bench_v2x import GN, typical_cam
from bench.figure import Better, Figure, Unit, ratio
from bench.sizes import sized
from bench.turn_about import seconds_per_call_in_turns
from bench.turn_spread import turn_ratio_spread
from coopdrive.v2x.btp import parse_btp_b
from coopdrive.recording.capture import read_capture
from coopdrive.v2x.geonet import BASIC_HEADER_SIZE, BasicNextHeader, parse_gn, with_basic_next_header
from coopdrive.v2x.packet import V2xPacketCodec
from coopdrive.v2x.security import asn
from coopdrive.v2x.security.certificate import Certificate
from coopdrive.v2x.security.envelope import TBS_OFFSET_IN_ENVELOPE, parse_signed_data
from tests.shared_data import shared_file

ROUNDS = sized(40, 1)
BATCH = sized(20, 2)
TARGET_RATIO = 1.3
PREHASHED = ec.ECDSA(Prehashed(hashes.SHA256()))


def bare_signed_cam(packet: bytes) -> Callable[[], object]:
    """asn1tools + hashlib + cryptography on a signed CAM whose layout is known beforehand."""
    envelope = packet[BASIC_HEADER_SIZE:]
    parsed = parse_signed_data(envelope)
    end_of_tbs = TBS_OFFSET_IN_ENVELOPE + len(parsed.tbs_bytes)
    certificate = parsed.certificate_bytes
    key = Certificate.from_bytes(certificate).public_key
    gn = parse_gn(with_basic_next_header(packet, BasicNextHeader.COMMON_HEADER, parsed.unsecured))
    uper_offset = len(parsed.unsecured) - len(parse_btp_b(gn.payload)[1])
    security, cam = asn.security_spec(), V2xPacketCodec().its_codec.spec(2)

    def decode():
        value = security.decode(asn.DATA_TYPE, envelope)
        signed = value["content"][1]
        digest = hashlib.sha256(hashlib.sha256(envelope[TBS_OFFSET_IN_ENVELOPE:end_of_tbs]).digest()
                                + hashlib.sha256(certificate).digest()).digest()
        signature = signed["signature"][1]
        r = int.from_bytes(signature["rSig"][1], "big")
        key.verify(encode_dss_signature(r, int.from_bytes(signature["sSig"], "big")), digest, PREHASHED)
        return cam.decode("CAM", signed["tbsData"]["payload"]["data"]["content"][1][uper_offset:])
    return decode


_BASIC, _COMMON, _SHB = struct.Struct(">BBBB"), struct.Struct(">BBBBHBB"), struct.Struct(">QIiiHHI")
_BTP, _ITS_HEADER = struct.Struct(">HH"), struct.Struct(">BBI")
_SHB_TYPE, _BTP_B, _CAM_PORT, _CAM_ID = 0x50, 2, 2001, 2
GN_HEADERS_SIZE = _BASIC.size + _COMMON.size + _SHB.size


def bare_unsigned_cam(spec) -> Callable[[bytes], object]:
    """The checks our path makes on an unsigned CAM, written out with struct, then asn1tools' decode."""
    def decode(packet: bytes):
        version_next, _, _, _ = _BASIC.unpack_from(packet, 0)
        if version_next >> 4 not in (0, 1) or version_next & 0x0F != 1:
            raise ValueError("basic header")
        next_header, header_type, _, _, payload_length, _, _ = _COMMON.unpack_from(packet, _BASIC.size)
        if header_type != _SHB_TYPE or next_header >> 4 != _BTP_B:
            raise ValueError("common header")
        _SHB.unpack_from(packet, _BASIC.size + _COMMON.size)
        if len(packet) - GN_HEADERS_SIZE < payload_length:
            raise ValueError("payload length")
        port, _ = _BTP.unpack_from(packet, GN_HEADERS_SIZE)
        uper = packet[GN_HEADERS_SIZE + _BTP.size:GN_HEADERS_SIZE + payload_length]
        version, message_id, _ = _ITS_HEADER.unpack_from(uper)
        if port != _CAM_PORT or message_id != _CAM_ID or version not in (1, 2):
            raise ValueError("port or message")
        return spec.decode("CAM", uper)
    return decode


def measure(seconds: float) -> list[tuple[str, int, list[float]]]:
    """Each path's name, packet size and CPU seconds per decode in each of ROUNDS turns about."""
    car_cam = list(read_capture(shared_file("v2x/considerit_signed_testvectors.pcap")))[1].gn_packet
    codec = V2xPacketCodec()
    assert codec.decode_frame(car_cam).security.verified
    unsigned = codec.encode_cam(typical_cam(), GN)
    uper = parse_btp_b(parse_gn(unsigned).payload)[1]
    cam_spec = codec.its_codec.spec(1)
    bare_unsigned = bare_unsigned_cam(cam_spec)
    rows = [("signed CAM: bare asn1tools + cryptography", len(car_cam), bare_signed_cam(car_cam)),
            ("signed CAM: ours, GN+security+UPER", len(car_cam), lambda: codec.decode_frame(car_cam)),
            ("signed CAM: ours, ... + protobuf", len(car_cam), lambda: codec.decode_packet(car_cam)),
            ("unsigned CAM: bare asn1tools UPER", len(uper), lambda: cam_spec.decode("CAM", uper)),
            ("unsigned CAM: bare struct checks + asn1tools", len(unsigned), lambda: bare_unsigned(unsigned)),
            ("unsigned CAM: ours, GN+BTP+UPER", len(unsigned), lambda: codec.decode_frame(unsigned))]
    per_turn_s = seconds_per_call_in_turns([operation for _, _, operation in rows], seconds, ROUNDS, BATCH)
    return [(path, size, each) for (path, size, _), each in zip(rows, per_turn_s)]


def main() -> list[Figure]:
    seconds = float(os.environ.get("BENCH_DECODE_SECONDS", sized(2.0, 0.05)))
    rows = measure(seconds)
    print(f"{'path':46} {'bytes':>5} {'decode/s':>9} {'x bare':>7}")
    rate = {path: 1.0 / min(turns_s) for path, _, turns_s in rows}
    turns_of = {path: turns_s for path, _, turns_s in rows}
    bare_signed, bare_uper, bare_like = rows[0][0], rows[3][0], rows[4][0]
    figures = []
    for path, size, _ in rows:
        bare = bare_signed if path.startswith("signed") else bare_like
        print(f"{path:46} {size:5d} {rate[path]:9.0f} {rate[bare] / rate[path]:7.2f}")
        figures.append(Figure(f"{path} decodes", rate[path], Unit.PER_S))
        if path != bare:
            # Each turn times both paths back to back: their per-turn ratios give the ratio's interval.
            figures.append(ratio(f"{path}: time x bare", rate[bare] / rate[path], bare, Better.LOWER,
                                 spread=turn_ratio_spread(turns_of[path], turns_of[bare])))
    ours = rate[rows[5][0]]
    verdict = "within" if rate[bare_like] / ours <= TARGET_RATIO else "NOT within"
    print(f"unsigned decode path: {rate[bare_like] / ours:.2f}x bare struct + asn1tools doing the same checks, "
          f"{verdict} the {TARGET_RATIO}x target ({rate[bare_uper] / ours:.2f}x asn1tools decoding the UPER alone)")
    print(f"signed CAM path (unwrap + verify + decode): {rate[bare_signed] / rate[rows[1][0]]:.2f}x bare")
    return figures


if __name__ == "__main__":
    main()
