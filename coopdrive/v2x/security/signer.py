"""Sign our CAM / DENM / iCLCM packets with an authorisation ticket, and change pseudonym.

    signer = SecuredPacketSigner(tickets)             # [(ticket certificate, private key), ...]
    packet = codec.encode_cam(content, GnParams(source_mac=signer.mac, ...))   # content.station_id = signer.station_id
    secured = signer.sign(packet, now_tai_us)

A pseudonym is a ticket, a station id and a MAC address changed together: changing one alone would let a
listener link old and new. Packets built with another pseudonym's station id or MAC are refused.
"""

from __future__ import annotations

import secrets
from collections.abc import Sequence
from contextlib import contextmanager
from dataclasses import dataclass

from cryptography.hazmat.primitives.asymmetric import ec

from coopdrive.v2x.btp import parse_btp_b
from coopdrive.v2x.geonet import MAC_SIZE_BYTES, BasicNextHeader, parse_gn, with_basic_next_header
from coopdrive.v2x.its_pdu import peek_its_header
from coopdrive.v2x.security.certificate import Certificate
from coopdrive.v2x.security.envelope import GenerationLocation, build_signed_data
from coopdrive.v2x.security.profile import (
    ELEVATION_UNKNOWN, FULL_CERTIFICATE_INTERVAL_S, PSID_DENM, PSID_OF_PORT)
from coopdrive.v2x.timebase import US_PER_S

STATION_ID_MODULUS = 2**32
_LOCALLY_ADMINISTERED, _MULTICAST = 0x02, 0x01


class PseudonymChangeRefused(RuntimeError):
    """rotate_pseudonym() while a manoeuvre holds the lock: partners must keep recognising us."""


@dataclass(frozen=True)
class Pseudonym:
    ticket: Certificate
    key: ec.EllipticCurvePrivateKey
    station_id: int
    mac: bytes


def random_mac() -> bytes:
    """A locally administered unicast MAC address."""
    mac = bytearray(secrets.token_bytes(MAC_SIZE_BYTES))
    mac[0] = (mac[0] | _LOCALLY_ADMINISTERED) & ~_MULTICAST & 0xFF
    return bytes(mac)


class SecuredPacketSigner:
    def __init__(self, tickets: Sequence[tuple[Certificate, ec.EllipticCurvePrivateKey]],
                 station_id: int | None = None, mac: bytes | None = None,
                 full_certificate_interval_s: float = FULL_CERTIFICATE_INTERVAL_S):
        if not tickets:
            raise ValueError("a signer needs at least one authorisation ticket")
        self._tickets = list(tickets)
        self._index = 0
        ticket, key = self._tickets[0]
        self._identity = Pseudonym(ticket, key, secrets.randbelow(STATION_ID_MODULUS) if station_id is None
                                   else station_id, random_mac() if mac is None else bytes(mac))
        self._interval_us = round(full_certificate_interval_s * US_PER_S)
        self._last_full_us: int | None = None
        self._full_requested = False
        self._locks: set[str] = set()
        self.signed_count = 0
        self.full_certificate_count = 0

    @property
    def identity(self) -> Pseudonym:
        return self._identity

    @property
    def station_id(self) -> int:
        return self._identity.station_id

    @property
    def mac(self) -> bytes:
        return self._identity.mac

    def request_full_certificate(self) -> None:
        """Send the full certificate with the next packet (a new station was heard, or asked for it)."""
        self._full_requested = True

    def sign(self, packet: bytes, now_tai_us: int) -> bytes:
        """The secured form of an unsecured GN packet of ours (basic header next header 2)."""
        gn = parse_gn(packet)
        btp, message = parse_btp_b(gn.payload)
        psid = PSID_OF_PORT.get(btp.destination_port)
        if psid is None:
            raise ValueError(f"no PSID for BTP port {btp.destination_port}")
        identity = self._identity
        position = gn.extended.source_position
        if position.address.mid != identity.mac:
            raise ValueError("packet built with another pseudonym's MAC address")
        if peek_its_header(message).station_id != identity.station_id:
            raise ValueError("packet built with another pseudonym's station id")
        location = None
        # TS 103 097 v1.3.1 7.1.2: a DENM always carries its certificate and its generation location.
        full = psid == PSID_DENM or self._full_due(now_tai_us)
        if psid == PSID_DENM:
            location = GenerationLocation(position.latitude_tenth_microdeg, position.longitude_tenth_microdeg,
                                          ELEVATION_UNKNOWN)
        elif full:
            self._last_full_us, self._full_requested = now_tai_us, False
        envelope = build_signed_data(packet[4:], psid, now_tai_us, identity.ticket, identity.key, full, location)
        self.signed_count += 1
        self.full_certificate_count += int(full)
        return with_basic_next_header(packet, BasicNextHeader.SECURED_PACKET, envelope)

    def _full_due(self, now_tai_us: int) -> bool:
        return self._full_requested or self._last_full_us is None or \
            now_tai_us - self._last_full_us >= self._interval_us or now_tai_us < self._last_full_us

    @contextmanager
    def manoeuvre_lock(self, name: str):
        """Hold the pseudonym during a manoeuvre (merge, platoon join): rotate_pseudonym() is refused."""
        self._locks.add(name)
        try:
            yield self
        finally:
            self._locks.discard(name)

    @property
    def locked_by(self) -> frozenset[str]:
        return frozenset(self._locks)

    def rotate_pseudonym(self) -> Pseudonym:
        """Switch to the next ticket with a fresh random station id and MAC; the next packet carries the
        full certificate so that neighbours learn the new ticket at once."""
        if self._locks:
            raise PseudonymChangeRefused(f"manoeuvre lock held by {', '.join(sorted(self._locks))}")
        if len(self._tickets) < 2:
            raise PseudonymChangeRefused("only one authorisation ticket: a change would not unlink anything")
        self._index = (self._index + 1) % len(self._tickets)
        ticket, key = self._tickets[self._index]
        station_id = self._identity.station_id
        while station_id == self._identity.station_id:
            station_id = secrets.randbelow(STATION_ID_MODULUS)
        self._identity = Pseudonym(ticket, key, station_id, random_mac())
        self._last_full_us = None
        return self._identity
