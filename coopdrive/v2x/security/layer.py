"""The security mode applied to packets in and out: the SecurityLayer that V2xPacketCodec(security=...) calls.

    layer = ModeSecurityLayer(SecurityMode.VERIFY_REQUIRED, verifier, signer, clock_tai_us)
    codec = V2xPacketCodec(security=layer)
    decoded = codec.decode_packet(packet)        # decoded.security: inspection.SecurityResult (UNSIGNED if unsigned)
    wire = layer.seal(codec.encode_cam(...))     # signed unless the mode is off

Every secured packet is unwrapped and its signature checked whenever the signer's key is known, in every mode
(inspection.py says what `verified`, `fresh` and `trusted` mean); the mode only decides what is dropped
(inspection.mode_drop_reason). A dropped packet raises V2xDecodeError, which the service counts as a rejection.
`status` counts verified packets, packets delivered with something wrong or unknown, and every reason.
clock_tai_us None: freshness is not judged (a codec without a configured clock).
"""

from __future__ import annotations

import time
from collections import OrderedDict
from collections.abc import Callable

from coopdrive.v2x.geonet import is_secured
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.inspection import UNSIGNED, PacketInspector, SecurityResult, mode_drop_reason
from coopdrive.v2x.security.profile import SecurityMode
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import US_PER_S, tai_ms_from_unix_s

# Signers remembered to notice a new station (then our next packet carries the full certificate).
HEARD_SIGNERS_REMEMBERED = 4096
MS_PER_US = 1000


def system_clock_tai_us() -> int:
    """TAI microseconds since 2004 from the system clock (ms resolution, as TimestampIts)."""
    return tai_ms_from_unix_s(time.time()) * MS_PER_US


class ModeSecurityLayer:
    """The packet codec's SecurityLayer (packet.py) for a SecurityMode: opens, checks and drops incoming
    packets as the mode says, and seals outgoing ones."""

    def __init__(self, mode: SecurityMode, verifier: SecurityVerifier | None = None,
                 signer: SecuredPacketSigner | None = None,
                 clock_tai_us: Callable[[], int] | None = system_clock_tai_us):
        if mode.signs and signer is None:
            raise ValueError(f"security mode {mode.value} needs a signer (authorisation ticket)")
        if verifier is None:
            raise ValueError("a security layer needs a verifier (certificate store), also to unwrap")
        self.mode, self.verifier, self.signer, self.clock_tai_us = mode, verifier, signer, clock_tai_us
        self.inspector = PacketInspector(verifier.store, verifier.max_age_us / US_PER_S,
                                         verifier.max_ahead_us / US_PER_S)
        self.delivered_unverified_count = 0
        self._heard: OrderedDict[bytes, None] = OrderedDict()

    def open(self, packet: bytes) -> tuple[bytes, SecurityResult]:
        """(the packet without its envelope, what its security says), or V2xDecodeError when the mode drops it."""
        if not is_secured(packet):  # the common case first: unsigned GCDC traffic costs one byte test
            if self.mode.drops_failures:
                self.verifier.rejected_by_reason[RejectReason.UNSECURED_PACKET_REFUSED] += 1
                raise V2xDecodeError(RejectReason.UNSECURED_PACKET_REFUSED, "security")
            return packet, UNSIGNED
        now_tai_us = self.clock_tai_us() if self.clock_tai_us is not None else None
        inspected = self.inspector.inspect(packet, now_tai_us)
        security = inspected.security
        self._count(security)
        drop = mode_drop_reason(self.mode, security)
        if drop is not None:
            raise V2xDecodeError(drop, "security")
        if inspected.unsecured_packet is None:
            raise V2xDecodeError(security.reason, "security")
        if security.reason is not None:
            self.delivered_unverified_count += 1
        return inspected.unsecured_packet, security

    def _count(self, security: SecurityResult) -> None:
        self._note_signer(security.signer_digest)
        if security.verified:
            self.verifier.verified_count += 1
        if security.reason is not None:
            self.verifier.rejected_by_reason[security.reason] += 1

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

