"""What the security layer found about one received packet, in the terms the station table and the bus use.

    verdict = verdict_of_opened(opened)                   # a packet the layer delivered (opened None: unsigned)
    verdict = verdict_of_refusal(packet, reason)          # a packet the layer's mode dropped
    sender = sender_of(packet, unwrap)                    # its MAC and station id, also inside a secured packet

`verified`: the signature was checked and is valid (True) or not (False); None when it could not be or was not
checked. `trusted`: the signer's certificate chains to a root we were given (True) or does not (False); None
when unknown. This module is the one place that reads the security layer's result type.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from coopdrive.v2x.btp import parse_btp_b
from coopdrive.v2x.geonet import is_secured, parse_gn
from coopdrive.v2x.its_pdu import peek_its_header
from coopdrive.v2x.reasons import RejectReason, V2xDecodeError

# Refusals that say the signature itself is wrong; that the signer's chain does not reach a root we trust; and,
# among those, that nobody we trust issued it. An unknown signer (digest never heard in full) or a stale
# generation time is neither: it says nothing against the station.
SIGNATURE_FAILURES = frozenset({RejectReason.INVALID_SIGNATURE.value})
UNTRUSTED_REASONS = frozenset({RejectReason.UNKNOWN_ISSUER.value, RejectReason.UNTRUSTED_ROOT.value, "untrusted"})
CHAIN_FAILURES = UNTRUSTED_REASONS | {reason.value for reason in (
    RejectReason.CERTIFICATE_EXPIRED, RejectReason.CERTIFICATE_NOT_YET_VALID, RejectReason.OUTSIDE_CERTIFICATE_REGION,
    RejectReason.PSID_NOT_PERMITTED, RejectReason.INVALID_CERTIFICATE_SIGNATURE, RejectReason.INVALID_CERTIFICATE)}

Unwrap = Callable[[bytes], bytes | None]


@dataclass(frozen=True, slots=True)
class SecurityVerdict:
    signed: bool
    verified: bool | None = None
    trusted: bool | None = None
    # Why it failed or could not be checked; None when nothing was wrong.
    reason: str | None = None


UNSIGNED = SecurityVerdict(False)


@dataclass(frozen=True, slots=True)
class Sender:
    mac: bytes | None
    station_id: int | None


def verdict_of_opened(opened) -> SecurityVerdict:
    """The verdict on a delivered packet from what the layer returned with it: None (it came unsigned), a
    result that answers signed / verified / trusted itself, or today's OpenedPacket (result.ok, verified)."""
    if opened is None:
        return UNSIGNED
    opened = getattr(opened, "security", opened)
    if hasattr(opened, "signed"):
        return SecurityVerdict(opened.signed, opened.verified, opened.trusted, _reason(opened.reason))
    result = opened.result
    reason = _reason(result.reason)
    if result.ok and not opened.verified:
        # Only unwrapped (modes off, sign_only): nothing was checked.
        return SecurityVerdict(True, None, None, reason)
    if not result.ok:
        return SecurityVerdict(True, False if reason in SIGNATURE_FAILURES else None,
                               False if reason in CHAIN_FAILURES else None, reason)
    # Verified by this layer means the chain reached a trusted root as well.
    return SecurityVerdict(True, True, True, reason)


def _reason(reason) -> str | None:
    return getattr(reason, "value", reason)


def verdict_of_refusal(packet: bytes, reason: RejectReason | str) -> SecurityVerdict:
    reason = _reason(reason)
    if not is_secured(packet):
        return SecurityVerdict(False, None, None, reason)
    return SecurityVerdict(True, False if reason in SIGNATURE_FAILURES else None,
                           False if reason in CHAIN_FAILURES else None, reason)


def sender_of(packet: bytes, unwrap: Unwrap | None = None) -> Sender:
    """The sender's GN source MAC and ITS station id, as far as the packet can be read (secured ones through
    unwrap, which opens the envelope without checking it)."""
    if is_secured(packet):
        packet = unwrap(packet) if unwrap is not None else None
        if packet is None:
            return Sender(None, None)
    try:
        gn = parse_gn(packet)
    except V2xDecodeError:
        return Sender(None, None)
    mac = bytes(gn.extended.source_position.address.mid)
    try:
        _, message = parse_btp_b(gn.payload)
        return Sender(mac, peek_its_header(message).station_id)
    except V2xDecodeError:
        return Sender(mac, None)
