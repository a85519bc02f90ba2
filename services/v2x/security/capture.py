"""Per-packet security report of a capture (pcap or pcapng), for `coopdrive v2x decode`.

Packets are verified in file order, so a digest signer resolves once its full certificate went by.
Freshness is judged against the capture's own timestamps (a capture is old by the time it is read).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import BinaryIO

from coopdrive.services.v2x.btp import parse_btp_b
from coopdrive.services.v2x.geonet import BASIC_HEADER_SIZE, BasicNextHeader, parse_gn
from coopdrive.services.v2x.packet import MESSAGE_OF_PORT
from coopdrive.services.v2x.capture import read_gn_packets
from coopdrive.services.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.services.v2x.security.layer import MS_PER_US
from coopdrive.services.v2x.security.store import CertificateStore
from coopdrive.services.v2x.security.verifier import SecurityVerifier
from coopdrive.services.v2x.timebase import tai_ms_from_unix_s

_NEXT_HEADER_MASK = 0x0F


@dataclass(frozen=True)
class PacketSecurity:
    index: int
    time_s: float
    # CAM / DENM / ICLCM when the (unwrapped) packet could be read that far.
    message: str | None
    signed: bool
    signer_digest: str | None
    full_certificate: bool | None
    # None: not signed, or no verifier given.
    verified: bool | None
    reason: RejectReason | None


def security_report(stream: BinaryIO, verifier: SecurityVerifier | None = None) -> Iterator[PacketSecurity]:
    """One PacketSecurity per GeoNetworking packet; without a verifier, signatures are not checked."""
    unwrapper = verifier or SecurityVerifier(CertificateStore())
    for index, captured in enumerate(read_gn_packets(stream)):
        packet = captured.gn_packet
        signed = len(packet) >= BASIC_HEADER_SIZE and \
            packet[0] & _NEXT_HEADER_MASK == BasicNextHeader.SECURED_PACKET
        if not signed:
            yield PacketSecurity(index, captured.time_s, _message(packet), False, None, None, None, None)
            continue
        verified, reason = None, None
        if verifier is not None:
            checked = verifier.open(packet, tai_ms_from_unix_s(captured.time_s) * MS_PER_US)
            verified, reason = checked.result.ok, checked.result.reason
        opened = unwrapper.unwrap(packet, count=False)
        if not opened.result.ok and reason is None:
            reason = opened.result.reason
        digest = opened.result.signer_digest
        yield PacketSecurity(index, captured.time_s, _message(opened.unsecured_packet), True,
                             digest.hex() if digest else None, opened.full_certificate, verified, reason)


def _message(packet: bytes | None) -> str | None:
    if packet is None:
        return None
    try:
        btp, _ = parse_btp_b(parse_gn(packet).payload)
    except V2xDecodeError:
        return None
    message = MESSAGE_OF_PORT.get(btp.destination_port)
    return message.name if message is not None else None
