"""100,000 random and mutated packets: decode_packet only ever raises V2xDecodeError, with a reason."""

import random
import struct
from collections import Counter

from coopdrive.v2x.geonet import GnPacket, parse_gn
from coopdrive.v2x.packet import (
    DestinationArea, GnParams, SourcePosition, decode_packet, encode_cam, encode_denm, encode_iclcm)
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

from .messages import cam, denm, iclcm

PACKETS = 100_000
SEED = 2016
GN = GnParams(source_mac=bytes.fromhex("020000000001"), source_position=SourcePosition(57.7, 11.9, 20.0, 1.0))
GBC = GnParams(source_mac=GN.source_mac, source_position=GN.source_position,
               destination_area=DestinationArea(57.7, 11.9, 500.0, 100.0, 0.3))


def seeds() -> list[bytes]:
    return [encode_cam(cam(False), GN), encode_cam(cam(True, 2), GN), encode_denm(denm(False), GBC),
            encode_denm(denm(False, 2), GN), encode_iclcm(iclcm(True), GN), encode_iclcm(iclcm(False), GN)]


def with_uper(packet: bytes, uper: bytes) -> bytes:
    gn = parse_gn(packet)
    return GnPacket(gn.basic, gn.common, gn.extended, gn.payload[:4] + uper).to_bytes()


def mutate(rng: random.Random, packet: bytes) -> bytes:
    data = bytearray(packet)
    kind = rng.randrange(8)
    if kind == 0:  # pure noise
        return rng.randbytes(rng.randrange(120))
    if kind == 1:  # truncation
        return bytes(data[:rng.randrange(len(data))])
    if kind == 2:  # bit flips anywhere
        for _ in range(rng.randint(1, 4)):
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    elif kind == 3:  # bit flips in the ASN.1 part, keeping the headers valid
        for _ in range(rng.randint(1, 3)):
            data[rng.randrange(44, len(data))] ^= 1 << rng.randrange(8)
    elif kind == 4:  # random ASN.1 behind valid headers
        return with_uper(packet, packet[44:50] + rng.randbytes(rng.randrange(80)))
    elif kind == 5:  # change a port, messageID or protocol version
        offset = rng.choice([40, 41, 44, 45])
        data[offset] = rng.randrange(256)
    elif kind == 6:  # insertions and deletions
        position = rng.randrange(len(data))
        if rng.random() < 0.5:
            data[position:position] = rng.randbytes(rng.randint(1, 8))
        else:
            del data[position:position + rng.randint(1, 8)]
    else:  # a header field set to an extreme
        offset = rng.randrange(12)
        data[offset] = rng.choice([0x00, 0xFF, 0x10, 0x12, 0x40, 0x66])
    return bytes(data)


def test_100000_mutated_packets_raise_only_v2x_decode_errors_each_counted_under_a_reason():
    rng = random.Random(SEED)
    originals = seeds()
    counts: Counter = Counter()
    for _ in range(PACKETS):
        packet = mutate(rng, rng.choice(originals))
        try:
            decode_packet(packet)
            counts["decoded"] += 1
        except V2xDecodeError as error:
            assert isinstance(error.reason, RejectReason)
            counts[error.reason.value] += 1
    assert sum(counts.values()) == PACKETS
    assert counts["decoded"] > 0
    # Each layer refused something: the mutator reaches every stage of the decoder.
    for reason in ("truncated_basic_header", "unsupported_gn_version", "payload_length_mismatch",
                   "unknown_btp_port", "malformed_asn1", "message_id_port_mismatch"):
        assert counts[reason] > 0, (reason, counts)


def test_every_seed_packet_decodes_unmutated():
    for packet in seeds():
        decode_packet(packet)


def test_a_structurally_valid_packet_on_an_unknown_port_names_the_port():
    """2006 is IVIM's port: named by capture decoding, not decoded (its module is not ours)."""
    packet = bytearray(encode_cam(cam(False), GN))
    struct.pack_into(">H", packet, 40, 2006)
    try:
        decode_packet(bytes(packet))
    except V2xDecodeError as error:
        assert error.reason == RejectReason.UNKNOWN_BTP_PORT and "2006" in str(error)
    else:
        raise AssertionError("decoded a packet on port 2006")
