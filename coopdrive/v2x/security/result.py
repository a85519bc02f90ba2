"""What the security layer found about one received packet (inspection.py's contract says what each field means),
and the checks every secured-packet format shares: freshness and where the sender was.

    result = SecurityResult(signed=True, signer="digest", signer_digest=..., reason=RejectReason.UNKNOWN_SIGNER_DIGEST)
    result.as_dict()                                            # the `security` object of `coopdrive v2x decode --json`
"""

from __future__ import annotations

from dataclasses import dataclass

from coopdrive.v2x.btp import parse_btp_b
from coopdrive.v2x.geonet import CommonNextHeader, parse_gn
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError
from coopdrive.v2x.security.envelope import GenerationLocation


@dataclass(frozen=True, slots=True)
class SecurityResult:
    signed: bool
    # "certificate" (sent in full), "digest", "self" (never verified), or (TS 103 097 v1.2.1) "certificate_chain";
    # None unsigned or unreadable.
    signer: str | None = None
    # HashedId8 of the signer's certificate.
    signer_digest: bytes | None = None
    verified: bool | None = None
    fresh: bool | None = None
    trusted: bool | None = None
    reason: RejectReason | None = None
    psid: int | None = None
    # TAI microseconds since 2004 (Time64), as signed.
    generation_time_us: int | None = None

    def as_dict(self) -> dict:
        """JSON-ready (the `security` object of `coopdrive v2x decode --json`)."""
        return {"signed": self.signed, "signer": self.signer,
                "signer_digest": self.signer_digest.hex() if self.signer_digest else None,
                "verified": self.verified, "fresh": self.fresh, "trusted": self.trusted,
                "reason": self.reason.value if self.reason else None, "psid": self.psid,
                "generation_time_us": self.generation_time_us}


UNSIGNED = SecurityResult(signed=False)


@dataclass(frozen=True, slots=True)
class InspectedPacket:
    security: SecurityResult
    # The GN packet without its envelope (the packet itself when unsigned); None when it cannot be unwrapped.
    unsecured_packet: bytes | None


def freshness_reason(envelope, now_tai_us: int | None, max_age_us: int, max_ahead_us: int) -> RejectReason | None:
    """Why the envelope's generation_time_us / expiry_time_us are not fresh at now_tai_us (None: fresh, or no clock)."""
    if now_tai_us is None:
        return None
    generated = envelope.generation_time_us
    if generated is None:
        return RejectReason.MISSING_GENERATION_TIME
    if generated > now_tai_us + max_ahead_us:
        return RejectReason.FUTURE_GENERATION_TIME
    expiry = envelope.expiry_time_us
    if now_tai_us - generated > max_age_us or (expiry is not None and now_tai_us > expiry):
        return RejectReason.STALE_GENERATION_TIME
    return None


def sender_position(location: GenerationLocation | None, unsecured: bytes) -> tuple[int | None, tuple[int, int] | None]:
    """(BTP destination port, (latitude, longitude) in 0.1 microdegree) as far as the packet can be read."""
    try:
        gn = parse_gn(unsecured)
        port = parse_btp_b(gn.payload)[0].destination_port if gn.common.next_header == CommonNextHeader.BTP_B \
            else None
        vector = gn.extended.source_position
        position = (vector.latitude_tenth_microdeg, vector.longitude_tenth_microdeg)
    except V2xDecodeError:
        port, position = None, None
    if location is not None:
        position = (location.latitude, location.longitude)
    return port, position
