"""Signed-CAM verification rate on one core: our full path against a bare `cryptography` ECDSA verify.

    python -m bench.bench_security [--seconds 1.0]

"full path" = basic header, OER decode of EtsiTs103097Data (signature and certificate spans checked
canonical), PSID/port, freshness, chain (cached after the first full certificate) and the ECDSA verify. The realistic
mix is a 10 Hz CAM stream with the full certificate once per second (1 packet in 10). The target is 100 stations at
10 Hz. The digest-signer ratio is also counted in instructions (bench/instructions_per_call.py), which guard it: two
quiet full runs of one commit moved its time by 13 %.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from collections.abc import Callable

from cryptography.hazmat.primitives import hashes
from cryptography.hazmat.primitives.asymmetric import ec

from bench.figure import Better, Figure, Unit, instruction_ratio, ratio
from bench.instructions_per_call import Workload, per_call
from bench.sizes import sized
from bench.turn_about import best_rates_per_s
from coopdrive.v2x.packet import GnParams, SourcePosition, V2xPacketCodec
from coopdrive.v2x.security.crypto import Curve
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import tai_ms_from_unix_s
from coopdrive.v1 import its_pb2

STATIONS = 100
CAM_RATE_HZ = 10
TARGET_PER_S = STATIONS * CAM_RATE_HZ
FULL_CERTIFICATE_SHARE = 1 / CAM_RATE_HZ
US_PER_MS = 1000
CAM_PERIOD_US = 100_000
ROUNDS = sized(3, 1)
BATCH = sized(50, 2)
# Verifies of each path whose instructions are counted (the same packet each time).
INSTRUCTION_CALLS = 50
INSTRUCTION_WORKLOADS = "bench.bench_security:instruction_workloads"
BARE_PATH, DIGEST_PATH = "bare cryptography ECDSA verify", "signed CAM, digest signer"


def signed_cams(curve: Curve, directory: str) -> tuple[SecurityVerifier, int, bytes, bytes]:
    pki = create_test_pki(directory, ["bench"], curve, tickets_per_vehicle=1)
    signer = pki.signer("bench", station_id=1001)
    content = its_pb2.CamContent(protocol_version=1, station_id=1001, station_type=5)
    content.reference_position.latitude_deg, content.reference_position.longitude_deg = 57.7089, 11.9735
    content.high_frequency.speed_mps, content.high_frequency.heading_rad = 22.2, 0.3
    packet = V2xPacketCodec().encode_cam(content, GnParams(
        source_mac=signer.mac, gn_version=1, source_position=SourcePosition(57.7089, 11.9735, 22.2, 0.3)))
    now = tai_ms_from_unix_s(time.time()) * US_PER_MS
    full = signer.sign(packet, now)
    digest = signer.sign(packet, now + CAM_PERIOD_US)
    verifier = SecurityVerifier(pki.store())
    assert verifier.verify(full, now).ok and verifier.verify(digest, now).ok
    return verifier, now, full, digest


def verify_calls(curve: Curve, directory: str) -> tuple[list[Callable[[], object]], list[int]]:
    """A bare `cryptography` verify of a digest-signed CAM's signed bytes with a key of the curve, and our full path's
    verify of a digest-signed and a certificate-signed CAM; and the bytes each verifies."""
    verifier, now, full, digest = signed_cams(curve, directory)
    key = ec.generate_private_key(curve.ec_curve())
    message = digest[4:]
    signature, public_key = key.sign(message, ec.ECDSA(hashes.SHA256())), key.public_key()
    return ([lambda: public_key.verify(signature, message, ec.ECDSA(hashes.SHA256())),
             lambda: verifier.verify(digest, now), lambda: verifier.verify(full, now)],
            [len(message), len(digest), len(full)])


# The workloads' test PKI, kept until the process that counts them exits.
_WORKLOAD_FOLDERS: list[tempfile.TemporaryDirectory] = []


def instruction_workloads() -> list[Workload]:
    _WORKLOAD_FOLDERS.append(tempfile.TemporaryDirectory(prefix="bench-security-"))
    workloads = []
    for curve in Curve:
        (bare, with_digest, _), _ = verify_calls(curve, f"{_WORKLOAD_FOLDERS[-1].name}/{curve.value}")
        workloads += [Workload(f"{curve.name} {BARE_PATH}", [bare] * INSTRUCTION_CALLS),
                      Workload(f"{curve.name} {DIGEST_PATH}", [with_digest] * INSTRUCTION_CALLS)]
    return workloads


def digest_ratios(curve: Curve, by_time: float, instructions: dict[str, float] | None) -> list[Figure]:
    """Our digest-signer verify over the bare one, in time and, where counted, in instructions (which guard it)."""
    name, baseline = f"{curve.name} {DIGEST_PATH}: time x bare verify", f"{curve.name} {BARE_PATH}"
    counted = None if instructions is None else instruction_ratio(
        name, instructions[f"{curve.name} {DIGEST_PATH}"] / instructions[f"{curve.name} {BARE_PATH}"], baseline)
    return ([] if counted is None else [counted]) + [
        ratio(name, by_time, baseline, Better.LOWER, guarded_by=None if counted is None else counted.name)]


def main() -> list[Figure]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=sized(1.0, 0.05), help="time per measurement")
    seconds = parser.parse_known_args()[0].seconds
    print(f"{'curve':18} {'path':34} {'bytes':>6} {'verify/s':>10}")
    verdicts, figures = [], []
    instructions = per_call(INSTRUCTION_WORKLOADS)
    with tempfile.TemporaryDirectory() as directory:
        for curve in Curve:
            calls, (message_bytes, digest_bytes, full_bytes) = verify_calls(curve, f"{directory}/{curve.value}")
            bare, with_digest, with_certificate = best_rates_per_s(calls, 3 * seconds, ROUNDS, BATCH)
            mix = 1 / (FULL_CERTIFICATE_SHARE / with_certificate + (1 - FULL_CERTIFICATE_SHARE) / with_digest)
            for path, size, rate in ((BARE_PATH, message_bytes, bare), (DIGEST_PATH, digest_bytes, with_digest),
                                     ("signed CAM, full certificate", full_bytes, with_certificate),
                                     ("10 Hz mix (1 in 10 with cert)", 0, mix)):
                print(f"{curve.name:18} {path:34} {size if size else '':>6} {rate:10.0f}")
                figures.append(Figure(f"{curve.name} {path}", rate, Unit.PER_S))
            figures += digest_ratios(curve, bare / with_digest, instructions)
            verdicts.append((curve, mix))
    for curve, mix in verdicts:
        fits = "fits" if mix >= TARGET_PER_S else "does NOT fit"
        print(f"{curve.name}: {STATIONS} stations x {CAM_RATE_HZ} Hz = {TARGET_PER_S} CAM/s {fits} on one core "
              f"({TARGET_PER_S / mix:.0%} of a core)")
    return figures


if __name__ == "__main__":
    main()
