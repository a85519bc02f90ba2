"""The security mode applied to packets in and out: what V2xPacketCodec(security=...) calls.

    layer = SecurityLayer(SecurityMode.VERIFY_REQUIRED, verifier, signer, clock_tai_us)
    codec = V2xPacketCodec(security=layer)
    decoded = codec.decode_packet(packet)        # decoded.security: OpenedPacket, or None if sent unsecured
    wire = layer.seal(codec.encode_cam(...))     # signed unless the mode is off

`verifier.rejected_by_reason` counts every security failure (also those still delivered in
sign_and_verify); a packet the mode drops raises V2xDecodeError, which the service counts as a rejection.
"""

from __future__ import annotations

import time
from collections import OrderedDict
from collections.abc import Callable

from coopdrive.services.v2x.geonet import BASIC_HEADER_SIZE, BasicNextHeader
from coopdrive.services.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.services.v2x.security.profile import SecurityMode
from coopdrive.services.v2x.security.signer import SecuredPacketSigner
from coopdrive.services.v2x.security.verifier import OpenedPacket, SecurityVerifier
from coopdrive.services.v2x.timebase import tai_ms_from_unix_s

_NEXT_HEADER_MASK = 0x0F
# Signers remembered to notice a new station (then our next packet carries the full certificate).
HEARD_SIGNERS_REMEMBERED = 4096
MS_PER_US = 1000


def system_clock_tai_us() -> int:
    """TAI microseconds since 2004 from the system clock (ms resolution, as TimestampIts)."""
    return tai_ms_from_unix_s(time.time()) * MS_PER_US


class SecurityLayer:
    def __init__(self, mode: SecurityMode, verifier: SecurityVerifier | None = None,
                 signer: SecuredPacketSigner | None = None,
                 clock_tai_us: Callable[[], int] = system_clock_tai_us):
        if mode.signs and signer is None:
            raise ValueError(f"security mode {mode.value} needs a signer (authorisation ticket)")
        if verifier is None:
            raise ValueError("a security layer needs a verifier (certificate store), also to unwrap")
        self.mode, self.verifier, self.signer, self.clock_tai_us = mode, verifier, signer, clock_tai_us
        self.delivered_unverified_count = 0
        self._heard: OrderedDict[bytes, None] = OrderedDict()

    def open(self, packet: bytes) -> tuple[bytes, OpenedPacket | None]:
        if len(packet) < BASIC_HEADER_SIZE or packet[0] & _NEXT_HEADER_MASK != BasicNextHeader.SECURED_PACKET:
            if self.mode.drops_failures:
                raise V2xDecodeError(RejectReason.UNSECURED_PACKET_REFUSED)
            return packet, None
        if not self.mode.verifies:
            return self._delivered(self.verifier.unwrap(packet))
        opened = self.verifier.open(packet, self.clock_tai_us())
        self._note_signer(opened.result.signer_digest)
        if opened.result.ok or self.mode.drops_failures:
            return self._delivered(opened)
        # sign_and_verify: deliver what failed verification (marked, verified=False) when it can be read.
        unwrapped = self.verifier.unwrap(packet, count=False)
        if unwrapped.result.ok:
            self.delivered_unverified_count += 1
            return unwrapped.unsecured_packet, OpenedPacket(
                opened.result, unwrapped.unsecured_packet, unwrapped.psid, unwrapped.generation_time_us,
                unwrapped.full_certificate, verified=False)
        return self._delivered(opened)

    def _note_signer(self, digest: bytes | None) -> None:
        if digest is None:
            return
        if digest in self._heard:
            self._heard.move_to_end(digest)
            return
        self._heard[digest] = None
        if len(self._heard) > HEARD_SIGNERS_REMEMBERED:
            self._heard.popitem(last=False)
        self.heard_new_station()

    @staticmethod
    def _delivered(opened: OpenedPacket) -> tuple[bytes, OpenedPacket]:
        if not opened.result.ok:
            raise V2xDecodeError(opened.result.reason, "security")
        return opened.unsecured_packet, opened

    def seal(self, packet: bytes, now_tai_us: int | None = None) -> bytes:
        """Our outgoing packet, signed when the mode signs."""
        if not self.mode.signs:
            return packet
        return self.signer.sign(packet, self.clock_tai_us() if now_tai_us is None else now_tai_us)

    def heard_new_station(self) -> None:
        """A station we had not heard before: send our full certificate with the next packet."""
        if self.signer is not None:
            self.signer.request_full_certificate()

    @property
    def status(self) -> dict[str, int]:
        return {"verified": self.verifier.verified_count, "delivered_unverified": self.delivered_unverified_count,
                **{reason.value: count for reason, count in self.verifier.rejected_by_reason.items()}}

