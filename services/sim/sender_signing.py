"""Signing what the simulator's own senders broadcast (scripted vehicles, roadside units) in secured runs.

Each sender signs with its own authorisation ticket from the run's test PKI, as a real vehicle or roadside
unit would, so a stack in "verify required" mode hears them; a stack holding an untrusted ticket is the only
one whose packets the others drop.
"""

from __future__ import annotations

import datetime as dt
from pathlib import Path

from coopdrive.services.sim.intent_encoder import station_mac
from coopdrive.v2x.geonet import is_secured
from coopdrive.services.sim.participants import MessageIntent
from coopdrive.v2x.security.pki import load_test_pki
from coopdrive.v2x.security.signer import SecuredPacketSigner
from coopdrive.v2x.security.verifier import SecurityVerifier
from coopdrive.v2x.timebase import ItsClock

US_PER_MS = 1000


class SenderSigning:
    def __init__(self, pki_dir: str | Path, utc_epoch: dt.datetime) -> None:
        self.pki = load_test_pki(pki_dir)
        self.clock = ItsClock(utc_epoch.timestamp())
        self._signers: dict[str, SecuredPacketSigner] = {}
        self._reader = SecurityVerifier(self.pki.store())

    def holds_ticket(self, sender_id: str) -> bool:
        return sender_id in self.pki.tickets

    def seal(self, intent: MessageIntent, packet: bytes) -> bytes:
        """The secured packet of an unsecured one the sender's intent was encoded to."""
        signer = self._signers.get(intent.sender_id)
        if signer is None:
            if intent.sender_id not in self.pki.tickets:
                raise KeyError(f"the run's PKI at {self.pki.directory} holds no ticket for sender {intent.sender_id!r}")
            signer = self.pki.signer(intent.sender_id, intent.station_id, station_mac(intent.station_id))
            self._signers[intent.sender_id] = signer
        return signer.sign(packet, self.clock.tai_ms(intent.time_s) * US_PER_MS)

    def unsecured(self, packet: bytes) -> bytes | None:
        """The GN packet inside a secured one (what a radio fault looks into); unsecured ones as they are."""
        if not is_secured(packet):
            return packet
        return self._reader.unwrap(packet, count=False).unsecured_packet
