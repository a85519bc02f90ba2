"""Mutated TS 103 097 v1.2.1 secured packets through the v2x service's whole receive path (receive_fuzz.py's
service and feed): GN version 0 CAMs and a DENM signed with a certificate, a certificate chain and a digest, and a
signed GN beacon, from keys of our own (tests/v2x/security/v121_vectors.py). The CI test runs V121_PACKETS; the
full run is

    .venv/bin/python -m tests.v2x.service.v121_receive_fuzz --packets 100000
"""

from __future__ import annotations

import random
import time
from pathlib import Path

from coopdrive.v2x.geonet import (
    BASIC_HEADER_SIZE, BasicHeader, BeaconHeader, CommonHeader, CommonNextHeader, GnAddress, GnPacket,
    LongPositionVector)
from coopdrive.v2x.security.pki import create_test_pki
from coopdrive.v2x.security.profile import PSID_DENM
from coopdrive.v2x.security.v121_reader import EccPointType
from coopdrive.v2x.timebase import generation_delta_time_ms, tai_ms_from_unix_s
from tests.v2x.messages import denm
from tests.v2x.security.signed import CODEC, cam, gn_params
from tests.v2x.security.v121_vectors import SUBJECT_AUTHORIZATION_AUTHORITY, Signer, V121Key, secure

from .receive_fuzz import FuzzOutcome, main, run_in_service

STATION_ID = 1202
US_PER_MS = 1000
# Octets a length code can start with: one more octet, two more, and the refused five more.
LENGTH_CODE_OCTETS = (0x80, 0xBF, 0xC0, 0xF8, 0xFF)
# The trailer: its length, its type, the algorithm, R (x only) and s.
TRAILER_SIZE = 1 + 1 + 1 + 1 + 32 + 32


class _Station:
    mac = b"\x02\x00\x00\x00\x12\x02"
    station_id = STATION_ID


def v121_seeds(now_s: float) -> list[bytes]:
    authority = V121Key.generate()
    authority_certificate = authority.issue(authority, subject_type=SUBJECT_AUTHORIZATION_AUTHORITY)
    ticket = authority.issue(V121Key.generate(), key_form=EccPointType.UNCOMPRESSED)
    now_tai_ms = tai_ms_from_unix_s(now_s)
    content = cam(STATION_ID)
    content.generation_delta_time_ms = generation_delta_time_ms(now_tai_ms)
    fresh_cam = CODEC.encode_cam(content, gn_params(_Station, gn_version=0))
    event = denm(False, 1)
    event.station_id = STATION_ID
    warning = CODEC.encode_denm(event, gn_params(_Station, gn_version=0))
    vector = LongPositionVector(GnAddress(mid=_Station.mac), now_tai_ms)
    beacon = GnPacket(BasicHeader(version=0), CommonHeader(next_header=CommonNextHeader.ANY),
                      BeaconHeader(vector), b"").to_bytes()
    generated_us = now_tai_ms * US_PER_MS
    return [secure(fresh_cam, ticket, Signer.CERTIFICATE, generated_us),
            secure(fresh_cam, ticket, Signer.DIGEST, generated_us, r_form=EccPointType.COMPRESSED_LSB_Y_0),
            secure(fresh_cam, ticket, Signer.CHAIN, generated_us, chain=(authority_certificate.encoded,)),
            secure(warning, ticket, Signer.DIGEST, generated_us, psid=PSID_DENM),
            secure(beacon, ticket, Signer.DIGEST, generated_us)]


def mutate_v121(rng: random.Random, packet: bytes) -> bytes:
    """One of: bit flips in the secured message, one in its signed CAM (a forgery), a cut, an octet inserted or
    deleted, an octet set to the start of a long length code."""
    data = bytearray(packet)
    choice = rng.randrange(5)
    if choice == 0:
        for _ in range(rng.randint(1, 4)):
            data[rng.randrange(BASIC_HEADER_SIZE, len(data))] ^= 1 << rng.randrange(8)
    elif choice == 1:
        start = max(BASIC_HEADER_SIZE, len(data) - 2 * TRAILER_SIZE)
        data[rng.randrange(start, len(data) - TRAILER_SIZE)] ^= 1 << rng.randrange(8)
    elif choice == 2:
        del data[rng.randrange(BASIC_HEADER_SIZE, len(data)):]
    elif choice == 3:
        position = rng.randrange(BASIC_HEADER_SIZE, len(data))
        if rng.random() < 0.5:
            del data[position]
        else:
            data.insert(position, rng.randrange(256))
    else:
        data[rng.randrange(BASIC_HEADER_SIZE, len(data))] = rng.choice(LENGTH_CODE_OCTETS)
    return bytes(data)


def run(packets: int, folder: Path) -> FuzzOutcome:
    now_s = time.time()
    create_test_pki(folder / "pki", ["ego"])
    return run_in_service(folder, now_s, [v121_seeds(now_s)], packets, mutate_v121)


if __name__ == "__main__":
    main(run, __doc__)
